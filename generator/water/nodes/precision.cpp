// Precision: the skeleton (water_shader.cpp) runs the shading math in a relaxed scope for
// "half"; geometry stays 32-bit. No node of its own.
#include "axis_tables.h"

namespace watergen {

AxisInfo precision_axis() {
    AxisInfo axis{
        "precision",
        "full",
        {
            {.name = "full",
             .description = "32-bit float everywhere",
             .gold = true,
             .scene_needs = {{SceneFact::Precision, "full", ""}}},
            {.name = "half",
             .description = "shading math in mediump / min16float (positions stay 32-bit)",
             .approximates = "full",
             .scene_needs = {{SceneFact::Precision, "half", ""}}},
        }};
    axis.permutation_only = true; // the types of all the shading change
    return axis;
}

} // namespace watergen
