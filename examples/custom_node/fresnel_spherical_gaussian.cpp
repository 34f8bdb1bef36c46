// A choice added to watergen's fresnel axis: Schlick's (1 - c)^5 replaced by a spherical
// Gaussian in c, 2^((-5.55473 c - 6.98316) c) (Karis, "Real Shading in Unreal Engine 4", 2013),
// one exp2 instead of the products. It reads watergen's own index parameters through their
// header: the same definitions are the same parameters, shared with schlick and exact.
#include "watergen/water/axis_registry.h"
#include "watergen/water/nodes/fresnel.h"
#include "watergen/water/surface.h"

namespace {

using namespace watergen;

Expr fresnel_spherical_gaussian(Graph& g, Expr c) {
    Expr n1 = uniform(g, ior_air());
    Expr n2 = uniform(g, ior_water());
    Expr r0 = named(square((n1 - n2) / (n1 + n2)), "fresnel_r0");
    Expr cs = named(saturate(c), "cos_view");
    return named(r0 + (1.0 - r0) * exp2((-5.55473 * cs - 6.98316) * cs), "fresnel");
}

} // namespace

WATERGEN_REGISTER_NODES(register_spherical_gaussian) {
    watergen::register_choice(
        "fresnel",
        feature_choice(
            {.name = "spherical_gaussian",
             .description = "Schlick with (1 - c)^5 as a spherical Gaussian (Karis 2013)",
             .approximates = "exact"},
            {{"c", Type::Float}}, &fresnel_spherical_gaussian,
            [](Surface& s) { s.fresnel = fresnel_spherical_gaussian(s.g, s.n_dot_v); }));
}
