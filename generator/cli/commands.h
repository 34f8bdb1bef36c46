// The CLI's subcommands. Each registers its options on the app and returns the function that
// runs it; main() only parses and dispatches.
#pragma once

#include <functional>
#include <map>
#include <optional>

#include <CLI/CLI.hpp>

#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/ir/diagnostic.h"
#include "watergen/ir/emitter.h"
#include "watergen/pipeline/variant_build.h"
#include "watergen/plan/material.h"
#include "watergen/plan/scene_file.h"
#include "watergen/runner/vulkan_runner.h"
#include "watergen/water/presets.h"
#include "watergen/water/variant.h"

namespace watergen::cli {

// Exit codes shared by every subcommand.
constexpr int kOk = 0;
constexpr int kFailed = 1;   // a shader failed to build or validate, or output could not be written
constexpr int kUsage = 2;    // bad flags or values
constexpr int kNoDevice = 3; // no Vulkan device (runner commands)

struct Common {
    DiagnosticFormat format = DiagnosticFormat::Gcc;
};

using Runner = std::function<int()>;

// A finite number within [lo, hi] (CLI::Range would let NaN through).
CLI::Validator finite_range(double lo, double hi);

// Adds --<axis> options for every axis, each restricted to its choices, and --preset.
void add_variant_options(CLI::App& app, Variant& variant, std::string& preset);
// Checks the variant's constraints and resolves the preset; prints the reason and returns
// false on bad input (exit with kUsage).
bool resolve_variant(const Variant& variant, const std::string& preset_name, const Preset** preset);
void print_diagnostics(const Diagnostics& ds, const Common& common);
// Adds --view NAME (scene_views.h), restricted to the registry's names; default beach.
void add_view_option(CLI::App& app, std::string& view);
// The synthetic scene at width x height seen from the view named `view` (one add_view_option
// accepted), its uniforms following the preset if any: a preset's values, its sun_direction
// among them, replace the view's.
SyntheticScene preset_scene(uint32_t width, uint32_t height, const Preset* preset,
                            const std::string& view = "beach");
// --draws (per variant and timing round, default 3), --cost-size (default 64) and --no-cost:
// the options of the commands that measure with compare's instrument.
void add_instrument_options(CLI::App& app, uint32_t& draws, uint32_t& cost_size, bool& cost);
// Adds --unroll hinted|all|none: the unroll hint every loop is emitted with.
void add_unroll_option(CLI::App& app, LoopUnroll& unroll);

struct RunnerSetup {
    std::string shader_cache = "off";
    std::string device;
};
void add_runner_options(CLI::App& app, RunnerSetup& setup);
// Applies the shader-cache choice (reported in *cache_used) and creates the runner; prints
// the reason and returns nullptr when there is no device (exit with kNoDevice).
std::unique_ptr<VulkanRunner> create_runner(const RunnerSetup& setup, std::string* cache_used);

Runner add_emit_command(CLI::App& app, const Common& common);
Runner add_render_command(CLI::App& app, const Common& common);
Runner add_probe_command(CLI::App& app, const Common& common);
Runner add_cost_command(CLI::App& app, const Common& common);
// The instructions lavapipe executes for one size x size draw (in the named view) of each
// variant's GLSL path, by key (a key given twice comes back a second time as "<key>#2": each its
// own pipeline, an A/A pair), counted under valgrind by a `watergen cost` worker (all variants in
// one run: about 5 s of JIT per variant); nullopt and *error when the worker failed.
std::optional<std::map<std::string, uint64_t>>
count_draw_costs(const std::vector<Variant>& variants, uint32_t size, const std::string& preset,
                 const std::string& view, std::string* error, bool strict_half = false);
// The body of a counting worker (run under valgrind): builds each key's variant with `build`
// and draws its GLSL path over `scene` once with the steady draw counted, labelled with the key
// ("<key>#2" for its second occurrence). Returns the exit code.
int draw_counted_keys(const std::vector<std::string>& keys, const SyntheticScene& scene,
                      const std::function<VariantBuild(const Variant&)>& build,
                      const Common& common);
Runner add_compare_command(CLI::App& app, const Common& common);
Runner add_caustics_command(CLI::App& app, const Common& common);
Runner add_pick_command(CLI::App& app, const Common& common);
// count_draw_costs for a material's shaders (path "" = the built-in material) as a build
// ships them: composed by the material and, with a scene file, folded under its facts (unless
// `folded` is false: bench prune's unpruned side); counted by `watergen pick` workers
// (pick_command.cpp), in the scene's conformed synthetic scene.
std::optional<std::map<std::string, uint64_t>>
count_material_costs(const std::string& material_path, const std::string& scene_path,
                     const std::vector<Variant>& variants, uint32_t size, std::string* error,
                     bool folded = true);
Runner add_bench_compile_command(CLI::App& bench, const Common& common);

// Material and scene files of build, explain and bench build / prune (build_command.cpp).
// An empty material path means the built-in default material. Prints the error and returns
// false on bad input (exit with kUsage).
bool load_material_and_scenes(const std::string& material_path,
                              const std::vector<std::string>& scene_paths, Material& material,
                              std::vector<SceneFacts>& scenes, const Common& common);
// --mode permutations|specialized|branching (build, bench modes).
void add_mode_option(CLI::App& app, std::string& mode);
Runner add_build_command(CLI::App& app, const Common& common);
Runner add_merge_command(CLI::App& app);
Runner add_explain_command(CLI::App& app, const Common& common);
Runner add_bench_build_command(CLI::App& bench, const Common& common);
Runner add_bench_prune_command(CLI::App& bench, const Common& common);
Runner add_bench_accuracy_command(CLI::App& bench, const Common& common);
Runner add_bench_half_command(CLI::App& bench, const Common& common);
Runner add_bench_cpu_command(CLI::App& bench, const Common& common);
Runner add_bench_unroll_command(CLI::App& bench, const Common& common);
Runner add_bench_modes_command(CLI::App& bench, const Common& common);

// Prints a bench's error diagnostics, or else its error; false when there was either.
bool bench_succeeded(const Diagnostics& diagnostics, const std::string& error,
                     const Common& common);

// Writes <out>/<stem>.csv and <out>/<stem>.json (each atomically) and says so; prints the
// error and returns false when one cannot be written (exit with kFailed).
bool write_bench_files(const std::string& out, const std::string& stem, const std::string& csv,
                       const std::string& json);

} // namespace watergen::cli
