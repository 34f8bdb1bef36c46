#include "watergen/water/nodes/fresnel.h"

#include <tuple>

#include "watergen/water/node_catalog.h"
#include "watergen/water/surface.h"

namespace watergen {

Parameter ior_air() {
    return {"ior_air", Type::Float, {1.0}, 1.0, 3.0, "", "000", ""};
}

Parameter ior_water() {
    return {"ior_water", Type::Float, {1.33333}, 1.0, 3.0, "", "000", ""};
}

Expr fresnel_none(Graph& g, Expr c) {
    OriginScope scope(g, "fresnel.none");
    (void)c;
    return uniform(g, {"fresnel_constant", Type::Float, {0.020408}, 0.0, 1.0, "", "000", ""});
}

Expr fresnel_power(Graph& g, Expr c) {
    OriginScope scope(g, "fresnel.power");
    Expr q = uniform(g, {"fresnel_power", Type::Float, {4.5}, 0.5, 16.0, "", "002", ""});
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

void append_fresnel_nodes(std::vector<CatalogNode>& list) {
    for (auto [name, f, what] : {std::tuple{"fresnel.none", &fresnel_none, "constant reflectance"},
                                 std::tuple{"fresnel.power", &fresnel_power, "(1 - c)^q"},
                                 std::tuple{"fresnel.schlick", &fresnel_schlick, "Schlick reflectance of c"},
                                 std::tuple{"fresnel.exact", &fresnel_exact, "exact unpolarised reflectance of c, with TIR"}})
        list.push_back({name, what, {{"c", Type::Float}},
                        [f](Graph& g, const std::vector<Expr>& in) { return f(g, in[0]); }});
}

void apply_fresnel(Surface& s, const std::string& choice) {
    if (choice == "none") s.fresnel = fresnel_none(s.g, s.n_dot_v);
    else if (choice == "power") s.fresnel = fresnel_power(s.g, s.n_dot_v);
    else if (choice == "schlick") s.fresnel = fresnel_schlick(s.g, s.n_dot_v);
    else if (choice == "exact") s.fresnel = fresnel_exact(s.g, s.n_dot_v);
    else s.g.error("fresnel: no node for choice '" + choice + "'");
}

} // namespace watergen
