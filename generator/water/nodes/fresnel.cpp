#include "watergen/water/nodes/fresnel.h"

#include "axis_tables.h"
#include "watergen/water/surface.h"

namespace watergen {

Parameter ior_air() {
    return {.name = "ior_air",
            .type = Type::Float,
            .default_value = {1.0},
            .min = 1.0,
            .max = 3.0,
            .seed = "000"};
}

Parameter ior_water() {
    return {.name = "ior_water",
            .type = Type::Float,
            .default_value = {1.33333},
            .min = 1.0,
            .max = 3.0,
            .seed = "000"};
}

Expr fresnel_none(Graph& g, Expr c) {
    OriginScope scope(g, "fresnel.none");
    (void)c;
    return uniform(g, {.name = "fresnel_constant",
                       .type = Type::Float,
                       .default_value = {0.020408},
                       .max = 1.0,
                       .seed = "000"});
}

Expr fresnel_power(Graph& g, Expr c) {
    OriginScope scope(g, "fresnel.power");
    Expr q = uniform(g, {.name = "fresnel_power",
                         .type = Type::Float,
                         .default_value = {4.5},
                         .min = 0.5,
                         .max = 16.0,
                         .seed = "002"});
    // pow(0, q) is 0 for q > 0 everywhere; the clamp keeps the base out of pow's undefined
    // negative range when c > 1 by rounding.
    return named(pow(saturate(1.0 - c), q), "fresnel");
}

Expr fresnel_schlick(Graph& g, Expr c) {
    OriginScope scope(g, "fresnel.schlick");
    Expr n1 = uniform(g, ior_air());
    Expr n2 = uniform(g, ior_water());
    Expr r0 = named(square((n1 - n2) / (n1 + n2)), "fresnel_r0");
    // (1 - c)^5 as products: no pow(0, y) edge case, and cheaper than pow on every target.
    Expr m = named(1.0 - saturate(c), "one_minus_c");
    Expr m2 = m * m;
    return named(r0 + (1.0 - r0) * (m2 * m2 * m), "fresnel");
}

Expr fresnel_exact(Graph& g, Expr c) {
    OriginScope scope(g, "fresnel.exact");
    Expr n1 = uniform(g, ior_air());
    Expr n2 = uniform(g, ior_water());
    Expr ci = named(saturate(c), "cos_incident");
    Expr s2 = named(square(n1 / n2) * (1.0 - ci * ci), "sin2_transmitted");
    Expr ct = named(sqrt(max(1.0 - s2, 0.0)), "cos_transmitted");
    // The denominators vanish only at grazing incidence past the critical angle, where the
    // select below returns 1; the max keeps the discarded branch finite all the same.
    const double tiny = 1e-30;
    Expr rs = (n1 * ci - n2 * ct) / max(n1 * ci + n2 * ct, tiny);
    Expr rp = (n2 * ci - n1 * ct) / max(n2 * ci + n1 * ct, tiny);
    Expr r = named(0.5 * (rs * rs + rp * rp), "fresnel_unpolarised");
    return named(select(s2 >= 1.0, constant(g, 1.0), r), "fresnel");
}

namespace {

// A choice whose node reads c = N.V and sets the surface's Fresnel term.
ChoiceInfo fresnel_choice(ChoiceInfo info, Expr (*node)(Graph&, Expr)) {
    return feature_choice(std::move(info), {{"c", Type::Float}}, node,
                          [node](Surface& s) { s.fresnel = node(s.g, s.n_dot_v); });
}

} // namespace

AxisInfo fresnel_axis() {
    // power and Schlick approximate the exact reflectance (water-models.md, "Fresnel").
    return {
        "fresnel",
        "schlick",
        {
            fresnel_choice({.name = "none", .description = "constant reflectance"}, &fresnel_none),
            fresnel_choice({.name = "power",
                            .seed = "002",
                            .description = "F = (1 - c)^q, q = 4.5",
                            .approximates = "exact"},
                           &fresnel_power),
            fresnel_choice({.name = "schlick",
                            .seed = "000",
                            .description = "Schlick's approximation, R0 from the indices",
                            .approximates = "exact"},
                           &fresnel_schlick),
            fresnel_choice(
                {.name = "exact",
                 .description = "unpolarised dielectric reflectance with total internal reflection",
                 .gold = true},
                &fresnel_exact),
        }};
}

} // namespace watergen
