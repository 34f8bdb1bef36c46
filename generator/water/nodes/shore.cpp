#include "watergen/water/nodes/shore.h"

#include "axis_tables.h"
#include "watergen/water/surface.h"

namespace watergen {

Expr shore_soft(Graph& g, Expr color, Expr refracted, Expr depth) {
    OriginScope scope(g, "shore.soft");
    // 000: blend back to the refracted scene near the shore; hardness 1 by default.
    Expr hardness = uniform(g, {.name = "shore_hardness",
                                .type = Type::Float,
                                .default_value = {1.0},
                                .max = 1e3,
                                .unit = "1/m",
                                .seed = "000"});
    return named(mix(refracted, color, saturate(max(depth, 0.0) * hardness)), "shore_color");
}

AxisInfo shore_axis() {
    return {
        "shore",
        "soft",
        {
            {.name = "hard", .seed = "000", .description = "the water colour up to the shoreline"},
            {.name = "soft",
             .seed = "000",
             .description = "blend towards the refracted scene by depth x shore hardness",
             .compose =
                 [](Surface& s) { s.color = shore_soft(s.g, s.color, s.refracted, s.depth); }},
        }};
}

} // namespace watergen
