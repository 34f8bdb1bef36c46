#include "watergen/water/nodes/specular.h"

#include <numbers>

#include "axis_tables.h"
#include "watergen/water/nodes/fresnel.h"
#include "watergen/water/surface.h"

namespace watergen {

namespace {

// Smallest normal binary16. A half GPU may flush anything below to zero, and x^s <= 2^-14 there
// for every exponent s >= 1, so cutting the lobe to 0 costs less than a half ulp of 1.
constexpr double kLobeFloor = 0x1p-14;
// Smallest GGX width: the sun lobe peaks near 1 / (18 a^3) at grazing mirror angles, which
// must stay below binary16's 65504 (a = 0.02 gives 7e3).
constexpr double kMinAlpha = 0.02;
// 1 / the N.V below which the GGX lobe fades out to 0 at grazing (specular_ggx_sun).
constexpr double kGrazingFade = 1024.0;

// The sun is above the horizon and in front of the surface.
Expr sun_lights(Expr to_sun, Expr n_dot_l) {
    return (to_sun.y() > 0.0) && (n_dot_l > 0.0);
}

} // namespace

Expr specular_lobe(Expr x, Expr exponent) {
    // Never pow(0, s): lavapipe, GPUs and C++ disagree on pow(0, 0) (water-models.md), and a
    // GPU that flushes denormals reads a tiny base as 0 while the CPU does not.
    Expr base = saturate(x);
    return select(base > kLobeFloor, pow(max(base, kLobeFloor), exponent),
                  constant(x.graph(), 0.0));
}

Expr half_vector(Expr a, Expr b) {
    // normalize(0) is NaN; near zero, dot(h, h) underflows in half precision. Scaling by the
    // largest component first makes the length >= 1 whenever h is not (nearly) zero.
    Expr h = a + b;
    Expr largest = max(max(abs(h.x()), abs(h.y())), abs(h.z()));
    Expr scaled = h / max(largest, 0x1p-24);
    Expr unit = scaled / max(length(scaled), 1.0);
    return select(largest > 0x1p-24, unit, constant(a.graph(), {0.0, 0.0, 0.0}));
}

Expr ggx_distribution(Expr n_dot_h, Expr sin2_h, Expr alpha) {
    Expr a2 = named(alpha * alpha, "ggx_alpha2");
    // d = ch^2 (a^2 - 1) + 1 written as sin^2 + ch^2 a^2: no cancellation near ch = 1 when sin^2
    // comes from |N x H|^2 (Filament's mediump form). d >= a^2, so k = a^2 / d is in (0, 1] and
    // D = k^2 / (pi a^2) never forms the 1 / d^2 that overflows binary16.
    Expr d = sin2_h + n_dot_h * n_dot_h * a2;
    Expr k = min(a2 / max(d, 0x1p-24), 1.0);
    return named(k * k / (std::numbers::pi * a2), "ggx_d");
}

Expr ggx_distribution(Expr n_dot_h, Expr alpha) {
    return ggx_distribution(n_dot_h, 1.0 - n_dot_h * n_dot_h, alpha);
}

Expr beckmann_distribution(Expr n_dot_h, Expr alpha) {
    // Below ch = 0.1 the lobe is < 1e-39 for every a <= 1 (exponent <= -99) while ch^4 would
    // underflow binary16: return 0 there.
    Expr c = clamp(n_dot_h, 0.1, 1.0);
    Expr c2 = c * c;
    Expr a2 = alpha * alpha;
    Expr d = exp((c2 - 1.0) / (a2 * c2)) / (std::numbers::pi * a2 * c2 * c2);
    return named(select(n_dot_h > 0.1, d, constant(n_dot_h.graph(), 0.0)), "beckmann_d");
}

Expr specular_toman_glare(Graph& g, const SpecularInputs& in) {
    OriginScope scope(g, "specular.toman_glare");
    // 000 suggests 0.5..0.7; the default is its upper end, 0.7.
    Expr shininess = uniform(g, {.name = "specular_shininess",
                                 .type = Type::Float,
                                 .default_value = {0.7},
                                 .max = 1.0,
                                 .seed = "000"});
    // 000's eyeVecNorm here points from the surface to the camera (V): M = 2 (V.N) N - V is the
    // mirrored view ray, and the glare peaks where it points at the sun (-L). With the
    // eye-to-point vector the glare would sit opposite the sun.
    Expr mirrored = named(2.0 * dot(in.to_eye, in.normal) * in.normal - in.to_eye, "mirrored_eye");
    Expr to_sun = -in.sun_travel;
    // d^512 amplifies the rounding of d = sat(M.(-L) 0.5 + 0.5) 512 times: one ulp of d near 1
    // (GPU and CPU normalise V an ulp apart) moves the glare by 3e-5 of its peak of 25. For unit
    // M and -L, 1 - d = |M + L|^2 / 4 without cancellation, and 1 - d^(2^k) follows
    // y <- y (2 - y) (= 1 - (1 - y)^2) with no cancellation either, nine times for 512.
    Expr gap = named(saturate(0.25 * dot(mirrored - to_sun, mirrored - to_sun)), "glare_gap");
    Expr y = gap;
    for (int i = 0; i < 9; ++i)
        y = y * (2.0 - y);
    Expr d512 = named(1.0 - y, "glare_lobe");
    // sat(-L.y) fades the glare out as the sun sets: 0 below the horizon.
    Expr s =
        named((1.0 - saturate(in.fresnel)) * saturate(to_sun.y()) * d512 * (shininess * 1.8 + 0.2),
              "glare");
    return named(s + s * 25.0 * saturate(shininess - 0.05), "specular_intensity");
}

Expr specular_blinn_phong(Graph& g, const SpecularInputs& in) {
    OriginScope scope(g, "specular.blinn_phong");
    // No seed gives one; 256 keeps the sun a small bright disc on calm water.
    Expr exponent = uniform(g, {.name = "specular_exponent",
                                .type = Type::Float,
                                .default_value = {256.0},
                                .min = 1.0,
                                .max = 8192.0});
    Expr to_sun = -in.sun_travel;
    // sun_travel = V (water-models.md's "L = -V", L pointing at the light: the sun straight
    // opposite the eye, below the surface) makes -L + V zero: half_vector returns 0 there.
    Expr h = named(half_vector(to_sun, in.to_eye), "half_vector");
    Expr lobe = specular_lobe(dot(in.normal, h), exponent);
    Expr lit = sun_lights(to_sun, dot(in.normal, to_sun));
    return named(select(lit, lobe, constant(g, 0.0)), "specular_intensity");
}

Expr specular_ggx_sun(Graph& g, const SpecularInputs& in) {
    OriginScope scope(g, "specular.ggx_sun");
    // GGX width a (not squared); 0.3, the roughness of water-models.md's microfacet goldens.
    Expr roughness = uniform(g, {.name = "specular_roughness",
                                 .type = Type::Float,
                                 .default_value = {0.3},
                                 .min = kMinAlpha,
                                 .max = 1.0});
    Expr n1 = uniform(g, ior_air());
    Expr n2 = uniform(g, ior_water());
    // Roughness 0 is a delta lobe (0 / 0 at N = H): clamp to the smallest width half can carry.
    Expr a = named(clamp(roughness, kMinAlpha, 1.0), "ggx_alpha");
    Expr a2 = a * a;
    Expr to_sun = -in.sun_travel;
    Expr n_dot_l = named(dot(in.normal, to_sun), "ggx_n_dot_l");
    Expr n_dot_v = named(dot(in.normal, in.to_eye), "ggx_n_dot_v");
    Expr h = named(half_vector(to_sun, in.to_eye), "half_vector");
    Expr n_cross_h = cross(in.normal, h);
    Expr d = ggx_distribution(saturate(dot(in.normal, h)), dot(n_cross_h, n_cross_h), a);
    // Separable Smith-GGX: G1(x) = 2x / (x + sqrt(a^2 + (1 - a^2) x^2)), so
    // G / (4 N.L N.V) * N.L = [N.L / (N.L + sqrt_l)] / (N.V + sqrt_v): no division by N.L N.V,
    // the first factor <= 1 and the second <= 1 / a.
    Expr nl = saturate(n_dot_l), nv = saturate(n_dot_v);
    Expr masked_l = nl / (nl + sqrt(a2 + (1.0 - a2) * nl * nl));
    Expr masked_v = 1.0 / (nv + sqrt(a2 + (1.0 - a2) * nv * nv));
    Expr visibility = named(masked_l * masked_v, "ggx_visibility");
    // Schlick on the microfacet angle V.H, R0 from the indices as fresnel.schlick does.
    Expr r0 = square((n1 - n2) / (n1 + n2));
    Expr m = 1.0 - saturate(dot(in.to_eye, h));
    Expr m2 = m * m;
    Expr f = named(r0 + (1.0 - r0) * (m2 * m2 * m), "ggx_fresnel");
    // N.V <= 0 (a back-facing normal from bumps) and N.L <= 0 are unlit, not extrapolated.
    // At N.L -> 0 the lobe goes to 0 with masked_l; at N.V -> 0 it does not (masked_v -> 1 / a):
    // cut there, a normal within float rounding of grazing would land on either side of a jump
    // of D F / a (1.3e-3 of a beach pixel at 512x512, the GPU dark and the CPU float lit). The
    // lobe fades out over N.V in (0, 2^-10] instead (the last 0.056 degrees before grazing).
    Expr grazing = named(saturate(n_dot_v * kGrazingFade), "ggx_grazing_fade");
    Expr lit = sun_lights(to_sun, n_dot_l);
    return named(select(lit, d * f * visibility * grazing, constant(g, 0.0)), "specular_intensity");
}

namespace {

// A sun lobe: the node gives the intensity, the surface's specular is that times the sun colour.
ChoiceInfo specular_choice(ChoiceInfo info, Expr (*node)(Graph&, const SpecularInputs&)) {
    info.scene_needs = {{SceneFact::SunAboveHorizon, "", "there is no sun highlight"}};
    const std::string origin = "specular." + info.name;
    return feature_choice(
        std::move(info),
        {{"normal", Type::Vec3},
         {"to_eye", Type::Vec3},
         {"sun_direction", Type::Vec3},
         {"fresnel", Type::Float}},
        node, [node, origin](Surface& s) {
            OriginScope scope(s.g, origin);
            Expr intensity = node(s.g, {s.normal, s.to_eye, s.sun_travel, s.fresnel});
            s.specular = named(intensity * s.sun_color, "specular");
        });
}

} // namespace

AxisInfo specular_axis() {
    // Blinn-Phong stands in for a microfacet lobe (its exponent plays the width, water-models.md
    // "Specular"); the glare is an artistic lobe of its own.
    return {
        "specular",
        "blinn_phong",
        {
            {.name = "none",
             .description = "no sun highlight",
             .compose =
                 [](Surface& s) {
                     OriginScope scope(s.g, "specular.none");
                     s.specular = constant(s.g, {0.0, 0.0, 0.0});
                 }},
            specular_choice({.name = "toman_glare",
                             .seed = "000",
                             .description = "reflected-eye glare, pow(d, 512) scaled by shininess"},
                            &specular_toman_glare),
            specular_choice(
                {.name = "blinn_phong", .description = "pow(N.H, s)", .approximates = "ggx_sun"},
                &specular_blinn_phong),
            specular_choice(
                {.name = "ggx_sun",
                 .seed = "004",
                 .description = "GGX microfacet sun lobe with Smith masking and Schlick Fresnel",
                 .gold = true},
                &specular_ggx_sun),
        }};
}

} // namespace watergen
