// The caustics pass (area ratio, after Evan Wallace's method as Unity HDRP's water ships it):
// a grid over the water surface, displaced by the same wave nodes as the water shader, each
// vertex moved to where the sunlight refracted through it meets a flat bottom, and drawn into
// the caustics texture with additive blending; each fragment adds the area ratio of its
// triangle, old (the beam's cross-section, projected along the light onto the water plane) over
// new (on the bottom), clamped to caustics_clamp. Overlapping (folded) triangles add up, as the
// light they carry does. Both stages are DSL graphs, emitted and validated like the water pass.
#pragma once

#include <string>

#include "watergen/ir/ir.h"

namespace watergen {

struct CausticsPass {
    std::string wave_model; // "sum_of_sines" or "gerstner"
    // Attribute grid_xz (vec2: the undisplaced grid point, m); outputs position (Vulkan clip
    // space of the caustics texture), landing (vec2, where the ray meets the bottom, m) and
    // offset (vec2, the beam point minus the landing point, m) and clamp (caustics_clamp).
    Graph vertex;
    // Varyings v_landing, v_offset, v_clamp; reads no parameter. Output color (vec4: the clamped
    // area ratio in rgb, 1 in a).
    Graph fragment;
};

// Parameters beside the wave model's and the water pass's (time, sun_direction, ior_water):
// caustics_depth (m, the bottom below the water level), caustics_window (vec3: the bottom window
// x0, z0 and size the texture covers, m) and caustics_clamp (the largest ratio a fragment adds;
// HDRP's 5). An unknown model records a diagnostic on the vertex graph.
CausticsPass build_caustics_pass(const std::string& wave_model);

} // namespace watergen
