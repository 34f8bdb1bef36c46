// The table of each axis file (water/nodes/<axis>.cpp), private to the water layer:
// axis_registry.cpp lists them once, in the order of a variant key.
#pragma once

#include "watergen/water/axis_registry.h"

namespace watergen {

AxisInfo fresnel_axis();
AxisInfo extinction_axis();
AxisInfo specular_axis();
AxisInfo foam_axis();
AxisInfo reflection_axis();
AxisInfo refraction_axis();
AxisInfo normals_axis();
AxisInfo waves_axis();
AxisInfo shore_axis();
AxisInfo precision_axis();
AxisInfo caustics_axis();
AxisInfo scene_input_axis();
AxisInfo geometry_axis();

} // namespace watergen
