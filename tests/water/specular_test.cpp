// Golden values and guards of the specular nodes, on the CPU.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <random>

#include "optics_support.h"
#include "watergen/water/nodes.h"

using namespace watergen;
using test::eval_catalog_node;
using test::eval_node;

namespace {

using V3 = std::array<double, 3>;
double dot3(const V3& a, const V3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
V3 unit(const V3& a) {
    const double l = std::sqrt(dot3(a, a));
    return {a[0] / l, a[1] / l, a[2] / l};
}
V3 scaled(const V3& a, double s) {
    return {a[0] * s, a[1] * s, a[2] * s};
}
V3 sum(const V3& a, const V3& b) {
    return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
double sat(double x) {
    return std::clamp(x, 0.0, 1.0);
}

struct Case {
    V3 n, v, l; // normal, to_eye, sun travel
    double f;
};

void append(std::vector<double>& t, const Case& c) {
    t.insert(t.end(),
             {c.n[0], c.n[1], c.n[2], c.v[0], c.v[1], c.v[2], c.l[0], c.l[1], c.l[2], c.f});
}

std::vector<double> tuples_of(const std::vector<Case>& cases) {
    std::vector<double> t;
    for (const auto& c : cases)
        append(t, c);
    return t;
}

// Deterministic lit-hemisphere configurations: N near up, V above N's plane, sun above the horizon.
std::vector<Case> random_cases(size_t n) {
    std::mt19937 rng(12345);
    auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * (rng() / 4294967296.0); };
    std::vector<Case> cases;
    while (cases.size() < n) {
        const V3 normal = unit({uniform(-0.4, 0.4), 1.0, uniform(-0.4, 0.4)});
        const V3 v = unit({uniform(-1, 1), uniform(0.02, 1), uniform(-1, 1)});
        const V3 l = unit({uniform(-1, 1), uniform(-1, -0.02), uniform(-1, 1)});
        cases.push_back({normal, v, l, uniform(0, 1)});
    }
    return cases;
}

double toman_reference(const Case& c, double shininess) {
    // 000's snippet with eyeVecNorm = V.
    const V3 m = sum(scaled(c.n, 2.0 * dot3(c.v, c.n)), scaled(c.v, -1.0));
    const double d = sat(-dot3(m, c.l) * 0.5 + 0.5);
    double s = (1.0 - c.f) * sat(-c.l[1]) * std::pow(d, 512.0) * (shininess * 1.8 + 0.2);
    return s + s * 25.0 * sat(shininess - 0.05);
}

double ggx_reference(const Case& c, double a, double r0) {
    // Textbook form: D G F / (4 N.L N.V) N.L with the divisions.
    const V3 to_sun = scaled(c.l, -1.0);
    const V3 h = unit(sum(to_sun, c.v));
    const double nl = dot3(c.n, to_sun), nv = dot3(c.n, c.v), ch = dot3(c.n, h), vh = dot3(c.v, h);
    if (nl <= 0 || nv <= 0 || to_sun[1] <= 0) return 0.0;
    const double a2 = a * a;
    const double d = a2 / (M_PI * std::pow(ch * ch * (a2 - 1) + 1, 2));
    auto g1 = [&](double x) { return 2 * x / (x + std::sqrt(a2 + (1 - a2) * x * x)); };
    const double f = r0 + (1 - r0) * std::pow(1 - vh, 5);
    // The node fades the lobe out over N.V in (0, 2^-10] (no jump at grazing).
    return d * g1(nl) * g1(nv) * f / (4 * nl * nv) * nl * std::min(nv * 1024.0, 1.0);
}

const double kR0 = std::pow((1.0 - 1.33333) / (1.0 + 1.33333), 2); // fresnel.h indices

std::vector<double> scalar_pairs(const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> t;
    for (double x : a)
        for (double y : b)
            t.insert(t.end(), {x, y});
    return t;
}

const std::vector<NodeInput> kPair = {{"x", Type::Float}, {"y", Type::Float}};

} // namespace

// water-models.md: D(1, 0.3) = 3.53677651, D(0.9, 0.3) = 0.39786114.
TEST_CASE("beckmann_distribution_matches_water_models_goldens", "[specular][golden]") {
    const auto r = eval_node(
        kPair,
        [](Graph&, const std::vector<Expr>& in) { return beckmann_distribution(in[0], in[1]); },
        {1.0, 0.3, 0.9, 0.3});
    CHECK(r[0] == Approx(3.53677651).epsilon(1e-8));
    CHECK(r[1] == Approx(0.39786114).epsilon(1e-8));
    CHECK(r[0] == Approx(1.0 / (M_PI * 0.09)).epsilon(1e-12));
}

TEST_CASE("ggx_distribution_matches_trowbridge_reitz_in_double", "[specular][golden]") {
    const std::vector<double> chs = {0.0, 0.2, 0.5, 0.9, 0.99, 1.0}, alphas = {0.02, 0.1, 0.3, 1.0};
    const auto r = eval_node(
        kPair, [](Graph&, const std::vector<Expr>& in) { return ggx_distribution(in[0], in[1]); },
        scalar_pairs(chs, alphas));
    size_t i = 0;
    for (double ch : chs)
        for (double a : alphas) {
            const double a2 = a * a;
            CHECK(r[i++] ==
                  Approx(a2 / (M_PI * std::pow(ch * ch * (a2 - 1) + 1, 2))).epsilon(1e-12));
        }
    // At N = H both lobes peak at 1 / (pi a^2): Beckmann's golden D(1, 0.3) again.
    const auto peak = eval_node(
        kPair, [](Graph&, const std::vector<Expr>& in) { return ggx_distribution(in[0], in[1]); },
        {1.0, 0.3});
    CHECK(peak[0] == Approx(3.53677651).epsilon(1e-8));
}

TEST_CASE("toman_glare_matches_the_000_snippet_in_double", "[specular][golden]") {
    auto cases = random_cases(400);
    // Put half of them near the mirror direction, where d^512 is not negligible.
    for (size_t i = 0; i < cases.size(); i += 2) {
        Case& c = cases[i];
        const V3 mirrored = sum(scaled(c.n, 2.0 * dot3(c.v, c.n)), scaled(c.v, -1.0));
        c.l = unit(sum(scaled(mirrored, -1.0), {0.01 * (i % 7), 0.0, -0.01 * (i % 5)}));
    }
    const auto r = eval_catalog_node("specular.toman_glare", tuples_of(cases));
    double peak = 0;
    for (size_t i = 0; i < cases.size(); ++i) {
        // The node computes 1 - d^512 without cancellation (see specular.cpp): it matches the
        // literal snippet relatively near the peak and to 1e-12 absolutely where d^512 is tiny.
        CHECK(r[i] == Approx(toman_reference(cases[i], 0.7)).epsilon(1e-12).margin(1e-12));
        peak = std::max(peak, r[i]);
    }
    CHECK(peak > 1.0); // the comparison saw real highlights, not only zeros
}

// 000's eyeVecNorm is the surface-to-camera vector at this point: the glare sits where the
// mirrored view ray meets the sun, at (1 - F) sat(-L.y) (1.8 s + 0.2)(1 + 25 (s - 0.05)).
TEST_CASE("toman_glare_peaks_where_the_mirrored_view_points_at_the_sun", "[specular][golden]") {
    const V3 n{0, 1, 0}, v = unit({0, 0.6, 0.8});
    const V3 mirror_sun{0, -0.6, 0.8}; // travels along the mirrored view ray, reversed
    const V3 opposite_sun{0, -0.6,
                          -0.8}; // behind the viewer: the seed's E = P - eye would light this
    const auto r = eval_catalog_node(
        "specular.toman_glare", tuples_of({{n, v, mirror_sun, 0.02}, {n, v, opposite_sun, 0.02}}));
    CHECK(r[0] == Approx(0.98 * 0.6 * (0.7 * 1.8 + 0.2) * (1 + 25 * 0.65)).epsilon(1e-12));
    CHECK(r[0] == Approx(14.80878).epsilon(1e-6));
    CHECK(r[1] < 1e-12); // d = 0.36: d^512 ~ 1e-227, within the lobe's one-ulp-of-1 floor
}

TEST_CASE("blinn_phong_matches_pow_n_dot_h_in_double", "[specular][golden]") {
    const auto cases = random_cases(400);
    const auto r = eval_catalog_node("specular.blinn_phong", tuples_of(cases));
    for (size_t i = 0; i < cases.size(); ++i) {
        const Case& c = cases[i];
        const V3 to_sun = scaled(c.l, -1.0);
        const double ch = dot3(c.n, unit(sum(to_sun, c.v)));
        const bool lit = dot3(c.n, to_sun) > 0;
        CHECK(r[i] ==
              Approx(lit ? std::pow(std::max(ch, 0.0), 256.0) : 0.0).epsilon(1e-11).margin(1e-300));
    }
}

TEST_CASE("ggx_sun_matches_the_textbook_microfacet_form_in_double", "[specular][golden]") {
    const auto cases = random_cases(400);
    for (double a : {0.05, 0.3, 0.8}) {
        const auto r = eval_catalog_node("specular.ggx_sun", tuples_of(cases),
                                         EvalPrecision::Double, {{"specular_roughness", {a}}});
        for (size_t i = 0; i < cases.size(); ++i)
            CHECK(r[i] == Approx(ggx_reference(cases[i], a, kR0)).epsilon(1e-11).margin(1e-300));
    }
}

// Guard: pow(0, 0) is 1 in C++ and NaN or 1 on GPUs (water-models.md): the lobe never calls
// pow with base 0 and is 0 there, whatever the exponent.
TEST_CASE("specular_lobe_is_zero_at_base_zero_even_for_exponent_zero", "[specular][guard]") {
    const std::vector<double> bases = {-0.5, 0.0, 1e-38, 1e-7}, exponents = {0.0, 1e-6, 1.0, 512.0};
    for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
        const auto r = eval_node(
            kPair, [](Graph&, const std::vector<Expr>& in) { return specular_lobe(in[0], in[1]); },
            scalar_pairs(bases, exponents), p);
        for (double v : r)
            CHECK(v == 0.0);
    }
}

// Guard: with L = -V in water-models.md's convention (to-sun = -V, our sun_travel = V),
// -L + V is the zero vector and normalize(0) is NaN.
TEST_CASE("half_vector_of_opposite_directions_is_zero_not_nan", "[specular][guard]") {
    const std::vector<NodeInput> two = {{"a", Type::Vec3}, {"b", Type::Vec3}};
    const V3 v = unit({0.3, 0.5, 0.8});
    for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
        const auto r = eval_node(
            two, [](Graph&, const std::vector<Expr>& in) { return half_vector(in[0], in[1]); },
            {v[0], v[1], v[2], -v[0], -v[1], -v[2], 1, 0, 0, 0, 1, 0}, p);
        for (int c = 0; c < 3; ++c)
            CHECK(r[c] == 0.0);
        CHECK(r[3] == Approx(std::sqrt(0.5)).epsilon(1e-3));
        CHECK(r[4] == Approx(std::sqrt(0.5)).epsilon(1e-3));
    }
    // And the nodes stay finite in that configuration, with the sun above or below the plane.
    for (const char* node : {"specular.toman_glare", "specular.blinn_phong", "specular.ggx_sun"}) {
        const V3 up{0, 1, 0};
        const auto r = eval_catalog_node(
            node, tuples_of({{up, v, v, 0.1}, {up, v, scaled(v, -1), 0.1}}), EvalPrecision::Float);
        for (double x : r)
            CHECK(std::isfinite(x));
        CHECK(r[0] == 0.0); // sun_travel = V: the sun is below the horizon
    }
}

// Guard: the harbour_at_night preset's sun travels upwards (0.2, 0.3, 0.93): no highlight, not
// NaN, on any normal; likewise a sun exactly on the horizon. Without the horizon gate a normal
// tilted towards the low sun would still light blinn_phong and ggx_sun.
TEST_CASE("specular_is_zero_with_the_sun_at_or_below_the_horizon", "[specular][guard]") {
    const std::vector<V3> suns = {
        {0.2, 0.3, 0.93}, unit({0.0, 0.05, 1.0}), {0.0, 0.0, 1.0}, {1.0, 0.0, 0.0}};
    std::vector<Case> cases;
    for (const V3& l : suns)
        for (const V3& n : {V3{0, 1, 0}, unit({0, 0.6, -0.8}), unit({-0.5, 0.7, -0.5})})
            for (const V3& v : {unit({0, 0.3, -1}), unit({0, 1, 0}), unit({0.2, 0.1, -1})})
                cases.push_back({n, v, l, 0.05});
    for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half})
        for (const char* node :
             {"specular.toman_glare", "specular.blinn_phong", "specular.ggx_sun"}) {
            INFO(node << " " << to_string(p));
            const auto r = eval_catalog_node(node, tuples_of(cases), p);
            for (double x : r)
                CHECK(x == 0.0);
        }
}

// Guard: a bumpy normal can face away from the eye or the sun; the microfacet terms are only
// defined for N.V > 0 and N.L > 0 and would otherwise return a positive (or negative) value.
TEST_CASE("ggx_sun_is_zero_when_n_dot_v_or_n_dot_l_is_not_positive", "[specular][guard]") {
    const V3 sun = unit({0.2, -0.5, -0.8});       // above the horizon, shining towards -z
    const V3 n_away_from_eye = unit({0, 0.3, 1}); // V below N's plane
    const V3 v = unit({0, 0.2, -1});
    const V3 n_away_from_sun = unit({0, 0.15, -1}); // N.(-L) < 0, N.V > 0
    std::vector<Case> cases = {{n_away_from_eye, v, sun, 0.0}, {n_away_from_sun, v, sun, 0.0}};
    REQUIRE(dot3(cases[0].n, v) < 0);
    REQUIRE(dot3(cases[0].n, scaled(sun, -1)) > 0);
    REQUIRE(dot3(cases[1].n, v) > 0);
    REQUIRE(dot3(cases[1].n, scaled(sun, -1)) < 0);
    // N.V = 0 exactly: grazing view.
    cases.push_back({{0, 1, 0}, {0, 0, -1}, sun, 0.0});
    for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
        const auto r = eval_catalog_node("specular.ggx_sun", tuples_of(cases), p);
        for (double x : r)
            CHECK(x == 0.0);
    }
}

// Guard: roughness 0 is a delta lobe, 0 / 0 at N = H. The width is clamped to 0.02, the
// smallest whose peak stays below binary16's 65504.
TEST_CASE("ggx_sun_at_roughness_zero_is_finite_and_equals_the_clamped_width", "[specular][guard]") {
    const V3 n{0, 1, 0}, v = unit({0, 0.6, 0.8});
    const std::vector<Case> cases = {{n, v, {0, -0.6, 0.8}, 0.0},
                                     {n, v, unit({0.01, -0.6, 0.8}), 0.0},
                                     {n, unit({0, 0.01, 1}), unit({0, -0.01, 1}), 0.0}};
    for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
        INFO(to_string(p));
        const auto zero = eval_catalog_node("specular.ggx_sun", tuples_of(cases), p,
                                            {{"specular_roughness", {0.0}}});
        const auto clamped = eval_catalog_node("specular.ggx_sun", tuples_of(cases), p,
                                               {{"specular_roughness", {0.02}}});
        for (size_t i = 0; i < zero.size(); ++i) {
            CHECK(std::isfinite(zero[i]));
            CHECK(zero[i] == clamped[i]);
            CHECK(zero[i] <= 1.0 / (M_PI * 0.02 * 0.02 * 0.02));
        }
        CHECK(zero[0] == Approx(ggx_reference(cases[0], 0.02, kR0))
                             .epsilon(p == EvalPrecision::Half ? 2e-2 : 1e-5));
    }
}

// Guard: in binary16 N.H rounds to 1 within 0.022 rad of the peak, so d = ch^2 (a^2 - 1) + 1
// collapses to a^2 and D to its peak: 390 % too high at a = 0.02 (measured). sin^2 taken from
// |N x H|^2 keeps the lobe's shape (measured 0.4 %).
TEST_CASE("ggx_lobe_keeps_its_shape_near_the_peak_in_half_precision", "[specular][guard]") {
    std::vector<Case> cases;
    const V3 n{0, 1, 0}, v = unit({0, 0.6, 0.8});
    for (int i = 0; i <= 60; ++i) {
        // Sun around the mirror direction, up to 0.06 rad off.
        const double off = i * 1e-3;
        cases.push_back({n, v, unit({std::sin(off), -0.6, 0.8}), 0.0});
    }
    const test::Uniforms narrow = {{"specular_roughness", {0.02}}};
    const auto half =
        eval_catalog_node("specular.ggx_sun", tuples_of(cases), EvalPrecision::Half, narrow);
    const auto exact =
        eval_catalog_node("specular.ggx_sun", tuples_of(cases), EvalPrecision::Double, narrow);
    double worst = 0;
    for (size_t i = 0; i < cases.size(); ++i)
        worst = std::max(worst, std::fabs(half[i] - exact[i]) / exact[i]);
    INFO("worst relative error " << worst);
    CHECK(worst < 0.03);
}

// Guard: the literal d^512 carries 512 times the rounding of d; in binary16 (ulp 2^-11 below 1)
// that is up to 28 % of the peak (measured 7.0 of 25.2). Computing 1 - d^512 without
// cancellation keeps half within 0.4 % of the peak (measured 0.2 %).
TEST_CASE("toman_glare_keeps_its_shape_in_half_precision", "[specular][guard]") {
    std::vector<Case> cases;
    const V3 n{0, 1, 0}, v = unit({0, 0.6, 0.8});
    for (int i = 0; i <= 200; ++i)
        cases.push_back({n, v, unit({i * 5e-4, -0.6, 0.8}), 0.0}); // up to 0.1 rad off the mirror
    const auto half =
        eval_catalog_node("specular.toman_glare", tuples_of(cases), EvalPrecision::Half);
    const auto exact =
        eval_catalog_node("specular.toman_glare", tuples_of(cases), EvalPrecision::Double);
    const double peak = exact[0];
    double worst = 0;
    for (size_t i = 0; i < cases.size(); ++i)
        worst = std::max(worst, std::fabs(half[i] - exact[i]));
    INFO("worst " << worst << " of a peak of " << peak);
    CHECK(worst < 0.004 * peak);
}
