// Texture sampling of the CPU evaluator, as the Vulkan spec defines it for the samplers the
// shaders use (clamp to edge, nearest or linear, 2D and cube maps). Private to ir/.
#pragma once

#include "watergen/ir/cpu/cpu_evaluator.h"

namespace watergen {

// out = the RGBA the sampler returns at (u, v); non-finite coordinates sample (0, 0).
void sample_2d(const TextureView& t, Filter filter, double u, double v, double out[4]);
// out = the RGBA of the cube map along direction (x, y, z), seams filtered across faces.
void sample_cube(const TextureView& t, Filter filter, double x, double y, double z, double out[4]);

} // namespace watergen
