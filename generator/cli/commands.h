// The CLI's subcommands. Each registers its options on the app and returns the function that
// runs it; main() only parses and dispatches.
#pragma once

#include <functional>
#include <map>
#include <optional>

#include <CLI/CLI.hpp>

#include "watergen/eval/draw/draw_device.h"
#include "watergen/eval/measure/gpu_cost.h"
#include "watergen/eval/measure/interleaved_timing.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/ir/core/diagnostic.h"
#include "watergen/ir/emit/emitter.h"
#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/plan/material.h"
#include "watergen/plan/scene_file.h"
#include "watergen/runner/vulkan_runner.h"
#include "watergen/runtime/water_grid.h"
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

// The command line: parses argv and runs the subcommand it names (main.cpp). An exception
// that escapes a subcommand ends it with its message and exit 1. run_with's `wrap` (for the
// tests) is given each subcommand's path ("bench geometry") and runner and returns what runs.
int run(int argc, char** argv);
using RunnerWrap = std::function<Runner(const std::string& path, Runner runner)>;
int run_with(int argc, char** argv, const RunnerWrap& wrap);
// Every subcommand's path, parents' subcommands (bench) left out.
std::vector<std::string> command_paths();

// A finite number within [lo, hi] (CLI::Range would let NaN through).
CLI::Validator finite_range(double lo, double hi);
// --jobs,-j N (0, the default: every hardware thread) and the count a run uses: N, or
// max_jobs() with a note on stderr when N is more (parallel_build.h).
void add_jobs_option(CLI::App& app, unsigned& jobs, const std::string& help);
unsigned capped_jobs(unsigned jobs);

// Adds --<axis> options for every axis, each restricted to its choices, and --preset.
void add_variant_options(CLI::App& app, Variant& variant, std::string& preset);
// Checks the variant's constraints, resolves the preset and composes the variant's IR (a
// project's node with a type error fails here, at its registering file and line); prints the
// reason and returns false on bad input (exit with kUsage).
bool resolve_variant(const Variant& variant, const std::string& preset_name, const Preset** preset,
                     const Common& common);
void print_diagnostics(const Diagnostics& ds, const Common& common);
// The exit code of a library run's status.
int exit_code(RunStatus status);
// Prints the diagnostics, then the error if any ("watergen: error: ..."); the status's exit code.
int stop(const Diagnostics& ds, const std::string& error, RunStatus status, const Common& common);
int stop(const std::string& error, RunStatus status);
// Adds --view NAME (scene_views.h), restricted to the registry's names; default beach.
void add_view_option(CLI::App& app, std::string& view);
// --draws (per variant and timing round, default 3), --cost-size (default 64) and --no-cost:
// the options of the commands that measure with compare's instrument.
void add_instrument_options(CLI::App& app, uint32_t& draws, uint32_t& cost_size, bool& cost);
// Adds --unroll hinted|all|none: the unroll hint every loop is emitted with.
void add_unroll_option(CLI::App& app, LoopUnroll& unroll);
// Adds --grid-spacing, --grid-rings and --grid-levels: the clipmap grid a mesh variant
// (geometry=mesh or tessellated) is drawn over (watergen/runtime/water_grid.h).
void add_grid_options(CLI::App& app, WaterGridDesc& grid);
// Prints why the grid is out of range ("watergen: error: --grid-*: ..."); false then.
bool check_grid(const WaterGridDesc& grid);
// Adds --tess-max: a tessellated variant's largest factor (RenderSettings::tess_max).
CLI::Option* add_tess_max_option(CLI::App& app, double& tess_max);
// A note that --tess-max was given for a variant that is not tessellated (it changes nothing).
void note_unused_tess_max(const CLI::Option* option, const Variant& variant);

// --shader-cache and --device.
using RunnerSetup = DrawDeviceChoice;
void add_runner_options(CLI::App& app, RunnerSetup& setup);
// open_draw_device (the shader-cache choice reported in *cache_used); prints the reason and
// returns nullptr when there is no device (exit with kNoDevice).
std::unique_ptr<VulkanRunner> create_runner(const RunnerSetup& setup, std::string* cache_used);
// Whether the device has shaderFloat16; prints "<device> has no shaderFloat16<why>" when not
// (exit with kNoDevice).
bool has_float16(const VulkanRunner& runner, const char* why);

Runner add_emit_command(CLI::App& app, const Common& common);
Runner add_render_command(CLI::App& app, const Common& common);
Runner add_probe_command(CLI::App& app, const Common& common);
Runner add_cost_command(CLI::App& app, const Common& common);
Runner add_gpu_worker_command(CLI::App& app);
// --target NAME (repeatable, or a comma list): the cost targets (gpu_target.h), lavapipe by
// default.
void add_target_option(CLI::App& app, std::vector<std::string>& targets);
// The targets named; prints the error and returns nullopt on an unknown one (exit kUsage).
std::optional<std::vector<GpuTarget>> resolve_targets(const std::vector<std::string>& words,
                                                      const std::string& flag = "--target");
// Whether every target's null device opened: prints each failure and returns the exit code
// (kNoDevice when a device is missing, kFailed for a worker that died), or kOk.
int check_target_runs(const std::vector<TargetCosts>& runs);
// What a cost per pixel counts on `target`, for the tables' headings.
std::string cost_unit(const GpuTarget& target);
// A target's costs as a table on stdout: per pipeline and stage, ACO's figures.
void print_gpu_costs(const TargetCosts& costs);
Runner add_compare_command(CLI::App& app, const Common& common);
Runner add_caustics_command(CLI::App& app, const Common& common);
Runner add_pick_command(CLI::App& app, const Common& common);
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
Runner add_bindings_command(CLI::App& app, const Common& common);
Runner add_bench_build_command(CLI::App& bench, const Common& common);
Runner add_bench_prune_command(CLI::App& bench, const Common& common);
Runner add_bench_accuracy_command(CLI::App& bench, const Common& common);
Runner add_bench_half_command(CLI::App& bench, const Common& common);
Runner add_bench_agreement_command(CLI::App& bench, const Common& common);
Runner add_bench_cpu_command(CLI::App& bench, const Common& common);
Runner add_bench_unroll_command(CLI::App& bench, const Common& common);
Runner add_bench_modes_command(CLI::App& bench, const Common& common);
Runner add_bench_geometry_command(CLI::App& bench, const Common& common);
Runner add_bench_stability_command(CLI::App& bench, const Common& common);

// Prints a bench's error diagnostics, or else its error; false when there was either.
bool bench_succeeded(const Diagnostics& diagnostics, const std::string& error,
                     const Common& common);

// "1.000 [0.980, 1.020]": a ratio with its interval, as the tables print them.
std::string interval_text(const RatioInterval& r);

// Writes <out>/<stem>.csv and <out>/<stem>.json (each atomically) and says so; prints the
// error and returns false when one cannot be written (exit with kFailed).
bool write_bench_files(const std::string& out, const std::string& stem, const std::string& csv,
                       const std::string& json);

} // namespace watergen::cli
