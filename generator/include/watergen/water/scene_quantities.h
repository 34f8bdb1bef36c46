// The quantities a scene can bound, as typed handles (Quantity, ir.h). The skeleton
// (water_shader.cpp) and the water column (surface.cpp) bind them where they create the nodes;
// the planner (plan/scene_pruning.cpp) attaches scene facts to them, never to node or
// parameter names, so renaming a temporary or a uniform cannot silently drop a fact.
#pragma once

#include "watergen/ir/core/ir.h"

namespace watergen::scene_quantity {

// Vertical water depth under the surface point, m (>= 0). True on water pixels only: the
// skeleton's final select(is_water, ...) discards every water term elsewhere.
inline constexpr Quantity water_depth{"water_depth", Type::Float, ""};
// Camera position, m: its y is bounded by the scene's camera height above the water level.
inline constexpr Quantity eye_position{"eye_position", Type::Vec3, "eye_position"};
// Height of the undisturbed water plane, m.
inline constexpr Quantity water_level{"water_level", Type::Float, "water_level"};
// Unit direction the sunlight travels: its y is bounded by the scene's sun elevation.
inline constexpr Quantity sun_direction{"sun_direction", Type::Vec3, "sun_direction"};
// Animation time, s: fixed to 0 when the scene's waves are static.
inline constexpr Quantity time{"time", Type::Float, "time"};

} // namespace watergen::scene_quantity
