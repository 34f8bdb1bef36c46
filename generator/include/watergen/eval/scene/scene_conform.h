// The synthetic scene made to obey a scene file's facts: what a shader folded under those facts
// is drawn over (pick, compare --scene, bench prune and their cost workers), so that it must
// draw what the unfolded shader draws.
#pragma once

#include <string>

#include "watergen/eval/scene/scene_views.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/plan/material.h"
#include "watergen/plan/scene_pruning.h"

namespace watergen {

// The synthetic scene changed where it contradicts the scene's facts, so that a shader folded
// under them must draw what the unpruned one draws: fixed parameters become its uniforms, the
// eye moves into the camera height range, the sun into the elevation range, and every water
// texel's scene point slides along its view ray into the depth range. `notes` says what moved.
SyntheticScene conform_scene(const SyntheticScene& base, const ScenePlan& plan,
                             const Material& material, std::string* notes = nullptr);

// Why the scene never shows `view`, or "" when it may: a camera pitch outside the scene's
// camera_pitch range. conform_scene() moves the eye height, the sun and the depths into the
// scene's ranges but keeps the view's framing, so such a view would measure the scene on
// pictures it says never happen; pick and compare --scene leave it out.
std::string view_outside_scene(const SceneView& view, const SceneFacts& facts);

} // namespace watergen
