// `watergen pick` for one scene as a library call: the scene's candidates (plan_pick) measured
// over every view it may show (conformed to its facts) against its gold, their instruction
// costs counted under valgrind (draw_cost.h) or compiled by an AMD family's ACO (gpu_cost.h),
// the cheapest within the budget picked, then the
// pick with each traded axis back at the gold's choice measured too (what each axis saved), and
// the pick written as a material file <out>/<scene>.json.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "watergen/eval/compare/pick.h"
#include "watergen/eval/draw/draw_device.h"
#include "watergen/eval/measure/gpu_target.h"
#include "watergen/runtime/water_grid.h"

namespace watergen {

struct PickRequest {
    std::string material_path; // "": the built-in material; the counting workers load it again
    std::map<std::string, std::string> hold; // axis -> choice held (plan_pick)
    PickBudget budget;
    uint32_t size = 256;     // image size of the error measurement
    uint32_t cost_size = 64; // image size of the instruction count
    WaterGridDesc grid{};    // the grid mesh candidates are drawn and counted over
    std::filesystem::path out = "out/pick";
    // Whose cost is traded: lavapipe's instructions per pixel counted under valgrind, or an AMD
    // family's fragment instructions from ACO, each loop weighted by its trip count
    // (gpu_cost.h: PipelineGpuCost::fragment_cost), of the GLSL path as the build ships it.
    GpuTarget target = *find_gpu_target("lavapipe");
};

struct PickSceneRun {
    std::vector<std::string> notes; // "view X left out: why"
    PickPlan pick;                  // every candidate measured and counted
    int chosen = -1;                // the pick's index in pick.candidates; -1: none within budget
    std::filesystem::path written;  // the material file, when a variant was picked
    std::string error;              // what stopped the measurement
    std::string write_error;        // the material file could not be written
    RunStatus status = RunStatus::Ok;
    bool measured() const { return error.empty(); }
};

// `material` and `plan` as loaded and planned from request.material_path and `scene_path` (the
// counting workers load them again).
// Cost: per candidate a variant build and a pipeline per view, a CPU double evaluation of the
// gold per view, and about 5 s of JIT under valgrind per candidate.
PickSceneRun pick_scene(VulkanRunner& runner, const Material& material, const ScenePlan& plan,
                        const std::string& scene_path, const PickRequest& request);

} // namespace watergen
