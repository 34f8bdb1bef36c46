// The steps of plan_scene that turn a scene's facts about parameters into fold facts: fixed
// values, static time, the camera height, the sun elevation and the water depth, each checked
// against the material's ranges and against the scene's own ranges. Private to plan/.
#pragma once

#include <optional>

#include "watergen/plan/scene_pruning.h"

namespace watergen::scene_bounds {

// Each returns the error (a Diagnostic at the scene fact) or nullopt, and adds its facts to
// plan.facts / plan.fixed.
std::optional<Diagnostic> fix_parameters(const Material& m, ScenePlan& plan);
std::optional<Diagnostic> bound_time(const Material& m, ScenePlan& plan);
std::optional<Diagnostic> bound_camera(const Material& m, ScenePlan& plan);
std::optional<Diagnostic> bound_sun(const Material& m, ScenePlan& plan);
void bound_depth(ScenePlan& plan);

} // namespace watergen::scene_bounds
