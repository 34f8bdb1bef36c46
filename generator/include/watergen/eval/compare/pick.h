// `watergen pick`: for a material and a scene, the cheapest variant the scene reaches whose
// error against the scene's gold stays within a budget. Cost is the load-free instruction count
// (draw_count.h) of the shader as a build for that scene ships it (composed by the material,
// folded under the scene's facts); error is measured over the views against the gold evaluated
// on the CPU in double precision.
//
// Only approximations are traded: the scene's gold takes, on every axis whose reached choices
// approximate the axis' gold (axis registry), that gold; every other axis varies between
// different models (flat or Gerstner waves, foam or none), a look the user decides, and is held
// at a given choice or else at the richest reached one (the last in the registry's order).
// Candidates are the reached variants that equal the gold on the held axes.
#pragma once

#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "watergen/eval/image/image_metrics.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/pipeline/build/build_output.h"
#include "watergen/plan/scene_pruning.h"
#include "watergen/runner/vulkan_runner.h"
#include "watergen/runtime/water_grid.h"

namespace watergen {

struct PickBudget {
    double max_de_p99 = 2.0;   // CIEDE2000 99th percentile, in every view
    double max_abs = INFINITY; // linear RGB, in every view
};

struct PickCandidate {
    Variant variant;
    std::string relation;      // to the gold (compare_run.h relation_to)
    double worst_de_p99 = 0;   // over the views
    double worst_max_abs = 0;  // over the views
    uint64_t nan_pixels = 0;   // over the views
    double cost_per_pixel = 0; // instructions per pixel (filled by the caller)
    // False for a variant measured only to compare with: the gold or a single-axis change of
    // the pick that the scene does not reach (the material does not offer it).
    bool reached = true;
    bool measured = false; // errors filled in by measure_pick_errors
    bool within(const PickBudget& b) const {
        return nan_pixels == 0 && worst_de_p99 <= b.max_de_p99 && worst_max_abs <= b.max_abs;
    }
};

struct PickPlan {
    Variant gold;
    std::vector<std::string> held; // axes held ("waves=gerstner (different models)")
    // The reached candidates (the gold first when reached), then the gold if unreached.
    std::vector<PickCandidate> candidates;
    size_t other_looks = 0; // reached variants that differ on a held axis
};

// The scene's gold and candidates. `hold` fixes held axes by name (axis -> choice).
PickPlan plan_pick(const ScenePlan& plan, const std::map<std::string, std::string>& hold = {});

// What:   renders every candidate (as build_for_scene builds it, build_output.h, GLSL path) over
// `views`
//         (scenes conformed to the plan) and compares each image with the gold's CPU double
//         evaluation of the same view; fills worst_de_p99, worst_max_abs and nan_pixels of
//         every candidate not yet measured.
// Output: "" or the first failure.
std::string measure_pick_errors(VulkanRunner& runner, const Material& material,
                                const ScenePlan& plan,
                                const std::vector<std::pair<std::string, SyntheticScene>>& views,
                                PickPlan& pick, const WaterGridDesc& grid = {});

// The index of the cheapest reached candidate within the budget (ties: the smaller error), or
// -1.
int cheapest_within(const std::vector<PickCandidate>& candidates, const PickBudget& budget);

// The candidates that would show what each axis of `chosen` saved: `chosen` with that axis at
// the gold's choice, added (unreached, unmeasured) where they are not candidates yet.
void add_axis_alternatives(PickPlan& pick, const Variant& chosen);

// The candidate equal to `base` except on `axis`, where it has `choice` (`base` itself for an
// empty axis); nullptr if none.
const PickCandidate* find_candidate(const PickPlan& pick, const Variant& base,
                                    const std::string& axis, const std::string& choice);

} // namespace watergen
