// The counting worker of a draw's instruction count (draw_count.h): the `watergen` executable
// run again under valgrind, told by its argv what to build and draw. This file owns both
// sides of that protocol: the argv a job is sent as, and the work the worker does. Two kinds:
// `watergen cost --counted` draws variants built as `watergen render` builds them, and
// `watergen pick --counted` a material's shaders as its build ships them; each command's
// hidden flags read the argv back into the job.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "watergen/eval/draw/draw_device.h"
#include "watergen/ir/emit/emitter.h"
#include "watergen/plan/scene_pruning.h"
#include "watergen/runtime/water_grid.h"
#include "watergen/water/variant.h"

namespace watergen {

// Variants built by build_variant with the preset (a half one in explicit 16-bit types with
// strict_half), drawn over the synthetic scene of the view at size x size under the preset.
struct VariantCountJob {
    // Without keys: this variant's GLSL and HLSL paths, each with its JIT span ("glsl first").
    Variant variant = default_variant();
    // Else these variants' GLSL paths, the steady draw only, labelled with the key ("<key>#2"
    // for its second occurrence: a second pipeline of it, an A/A pair).
    std::vector<std::string> keys;
    uint32_t size = 256;
    std::string preset, view = "beach"; // preset by name, "" for none
    LoopUnroll unroll = LoopUnroll::AsHinted;
    bool strict_half = false;
    // A mesh variant's grid and largest tessellation factor (RenderSettings::grid, tess_max).
    WaterGridDesc grid{};
    double tess_max = 0;
};

// The keys' shaders as a build of the material ships them: composed by it and, for a scene,
// folded under the scene's facts (unless !folded), drawn in the scene's conformed synthetic
// scene at size x size (beach view); GLSL path, steady draw, labelled as VariantCountJob's keys.
struct MaterialCountJob {
    std::string material_path; // "": the built-in material
    std::string scene_path;    // "": none (the material's shaders unfolded)
    bool folded = true;
    uint32_t size = 64;
    std::vector<std::string> keys;
    WaterGridDesc grid{}; // a mesh variant's (RenderSettings::grid)
};

// `<executable> cost --counted ...` and `<executable> pick --counted ...` (paths made
// absolute: the worker runs in a scratch directory of its own).
std::vector<std::string> count_worker_argv(const VariantCountJob& job,
                                           const std::filesystem::path& executable);
std::vector<std::string> count_worker_argv(const MaterialCountJob& job,
                                           const std::filesystem::path& executable);

// This process's own executable: the worker every count spawns.
std::filesystem::path own_executable();

struct CountWorkerRun {
    Diagnostics diagnostics; // of every build, in build order
    std::string error;       // what stopped it; "" when every draw was counted
    RunStatus status = RunStatus::Ok;
};

// The worker's work: refuses to run outside valgrind (bad input), opens the device with Mesa's
// shader cache off, builds and draws each job's shaders with the count on.
CountWorkerRun run_count_worker(const VariantCountJob& job);
// `material` and `plan` (nullptr: no scene) as loaded from the job's files.
CountWorkerRun run_count_worker(const MaterialCountJob& job, const Material& material,
                                const ScenePlan* plan);

} // namespace watergen
