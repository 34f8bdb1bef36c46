// A small fragment graph with one parameter marked as specialization constants (a vec3) and one
// left in the uniform block (a float), for the emission and toolchain tests.
#pragma once

#include "watergen/ir/core/dsl.h"

namespace watergen::test {

inline Parameter tint_parameter() {
    Parameter tint{.name = "tint",
                   .type = Type::Vec3,
                   .default_value = {0.25, -0.5, 2.0},
                   .min = -1.0,
                   .max = 4.0,
                   .origin = "test.tint"};
    tint.specialization = true;
    return tint;
}

inline Parameter gain_parameter() {
    return {.name = "gain",
            .type = Type::Float,
            .default_value = {2.0},
            .max = 8.0,
            .origin = "test.gain"};
}

// color = vec4(tint * gain * v_uv.x, 1)
inline Graph tint_graph() {
    Graph g;
    const Expr uv = varying(g, "v_uv", Type::Vec2);
    const Expr tint = uniform(g, tint_parameter()); // declared first: ids 0..2
    const Expr rgb = tint * uniform(g, gain_parameter()) * uv.x();
    g.set_output("color", vec4(rgb, constant(g, 1.0)).id());
    return g;
}

} // namespace watergen::test
