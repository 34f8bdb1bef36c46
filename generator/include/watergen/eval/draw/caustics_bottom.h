// The lit bottom of a caustics variant: the scene as the camera sees it, without the water
// surface, each pixel under the water level scaled by mix(1, I, caustics_strength) with I the
// caustics intensity at its bottom point, exactly as the variant's caustics node computes it
// (its own graph, evaluated on the CPU over the scene's textures: the tile for `texture`, the
// caustics_map for area_ratio and photon_splat). Shows where the light falls and how it is
// sampled, free of refraction, extinction and reflection.
#pragma once

#include <string>

#include "watergen/eval/image/image_io.h"
#include "watergen/eval/scene/synthetic_scene.h"

namespace watergen {

// The image at the scene's size, linear rgb, in float like the GPU; empty with the reason in
// *error for a choice without caustics ("none", unknown) or an evaluator failure.
ImageRGBA32F caustics_lit_bottom(const std::string& caustics_choice, const SyntheticScene& scene,
                                 std::string* error);

} // namespace watergen
