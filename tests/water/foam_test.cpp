// Golden values and guards of the foam nodes and the foam pattern, on the CPU.
#include <catch2/catch.hpp>

#include <cmath>

#include "optics_support.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/water/axis_registry.h"
#include "watergen/water/nodes.h"
#include "watergen/water/surface.h"

using namespace watergen;
using test::eval_catalog_node;

namespace {

// Coverage f alone: colour 0, pattern 1 and foam colour 1 make the output f in every channel.
std::vector<double> coverage(const std::string& node,
                             const std::vector<std::pair<double, double>>& depth_height,
                             const test::Uniforms& overrides = {},
                             EvalPrecision p = EvalPrecision::Double) {
    std::vector<double> t;
    for (auto [depth, height] : depth_height)
        t.insert(t.end(), {0.0, 0.0, 0.0, 1.0, depth, height});
    test::Uniforms u = overrides;
    u["foam_color"] = {1.0, 1.0, 1.0};
    const auto rgb = eval_catalog_node(node, t, p, u);
    std::vector<double> f;
    for (size_t i = 0; i < rgb.size(); i += 3)
        f.push_back(rgb[i]);
    return f;
}

SyntheticScene foam_scene() {
    SyntheticScene scene;
    add_foam_inputs(scene);
    return scene;
}

} // namespace

// 000, e = (0.45, 4.35, 1.5): full foam down to 0.45 m, none from 4.35 m, linear between.
TEST_CASE("shore_foam_is_full_to_e_x_and_fades_linearly_to_e_y", "[foam][golden]") {
    const auto f = coverage("foam.shore", {{-1e-3, 0},
                                           {0, 0},
                                           {0.2, 0},
                                           {0.45, 0},
                                           {2.4, 0},
                                           {3.375, 0},
                                           {4.35, 0},
                                           {10, 0},
                                           {INFINITY, 0}});
    const std::vector<double> expected = {1, 1, 1, 1, 0.5, 0.25, 0, 0, 0};
    for (size_t i = 0; i < f.size(); ++i)
        CHECK(f[i] == Approx(expected[i]).margin(1e-12));
}

// 000: f = sat((h - (h0 + e.z)) / (Hmax - e.z)), h above the water level (h0 = 0), Hmax = 3 m.
TEST_CASE("crest_foam_ramps_from_e_z_to_the_maximum_height", "[foam][golden]") {
    const auto f =
        coverage("foam.crest", {{5, -2}, {5, 0}, {5, 1.5}, {5, 1.875}, {5, 2.25}, {5, 3}, {5, 40}});
    const std::vector<double> expected = {0, 0, 0, 0.25, 0.5, 1, 1};
    for (size_t i = 0; i < f.size(); ++i)
        CHECK(f[i] == Approx(expected[i]).margin(1e-12));
}

TEST_CASE("both_foams_add_and_saturate", "[foam][golden]") {
    const auto f = coverage("foam.both", {{3.375, 1.875}, {2.4, 2.25}, {0, 3}, {10, 0}});
    const std::vector<double> expected = {0.5, 1, 1, 0};
    for (size_t i = 0; i < f.size(); ++i)
        CHECK(f[i] == Approx(expected[i]).margin(1e-12));
}

// colour = mix(colour, foam_color pattern, f).
TEST_CASE("foam_blends_the_tinted_pattern_over_the_colour", "[foam][golden]") {
    const auto r = eval_catalog_node("foam.shore", {0.2, 0.4, 0.6, 0.7, 2.4, 0.0},
                                     EvalPrecision::Double, {{"foam_color", {1.0, 0.5, 0.0}}});
    CHECK(r[0] == Approx(0.2 + (0.7 - 0.2) * 0.5).epsilon(1e-12));
    CHECK(r[1] == Approx(0.4 + (0.35 - 0.4) * 0.5).epsilon(1e-12));
    CHECK(r[2] == Approx(0.6 + (0.0 - 0.6) * 0.5).epsilon(1e-12));
}

// Guard (000 draws crest foam only when Hmax - e.z > 0): a non-positive span must give no
// foam, not a division by zero, and not foam everywhere above e.z.
TEST_CASE("crest_foam_is_zero_when_the_maximum_height_is_not_above_e_z", "[foam][guard]") {
    const std::vector<std::pair<double, double>> heights = {
        {5, -1}, {5, 0}, {5, 1.5}, {5, 2}, {5, 100}};
    for (double h_max : {1.5, 1.0, 0.0})
        for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
            INFO("Hmax " << h_max << " " << to_string(p));
            for (double f : coverage("foam.crest", heights, {{"foam_max_height", {h_max}}}, p))
                CHECK(f == 0.0);
        }
}

// Guard: e.y <= e.x would divide by zero (or by a negative span) in the shore fade; it is a
// hard edge at e.x instead.
TEST_CASE("shore_foam_is_a_step_at_e_x_when_e_y_is_not_beyond_it", "[foam][guard]") {
    for (auto e : {std::vector<double>{1.0, 1.0, 1.5}, std::vector<double>{2.0, 1.0, 1.5}})
        for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
            INFO("e = (" << e[0] << ", " << e[1] << ") " << to_string(p));
            const auto f = coverage("foam.shore",
                                    {{0, 0}, {0.5 * e[0], 0}, {e[0], 0}, {e[0] + 0.5, 0}, {50, 0}},
                                    {{"foam_existence", e}}, p);
            const std::vector<double> expected = {1, 1, 0, 0, 0};
            for (size_t i = 0; i < f.size(); ++i)
                CHECK(f[i] == expected[i]);
        }
}

TEST_CASE("foam_pattern_texture_is_periodic_smooth_and_in_range", "[foam][golden]") {
    const SyntheticScene scene = foam_scene();
    const TextureData& t = scene.textures.at("foam_pattern");
    const uint32_t n = kFoamPatternSize;
    REQUIRE(t.width == n);
    REQUIRE(t.height == n);
    double lo = 1, hi = 0, step = 0;
    auto at = [&](uint32_t x, uint32_t y) { return double(t.rgba[(size_t(y) * n + x) * 4]); };
    for (uint32_t y = 0; y < n; ++y)
        for (uint32_t x = 0; x < n; ++x) {
            lo = std::min(lo, at(x, y));
            hi = std::max(hi, at(x, y));
            if (x + 1 < n) step = std::max(step, std::fabs(at(x + 1, y) - at(x, y)));
            if (y + 1 < n) step = std::max(step, std::fabs(at(x, y + 1) - at(x, y)));
        }
    CHECK(lo >= 0.2);
    CHECK(hi <= 1.0);
    CHECK(hi - lo > 0.5); // not flat
    CHECK(step < 0.05);   // band-limited: no texel-scale noise (measured 0.023)
    for (uint32_t i = 0; i < n; ++i) {
        CHECK(at(n - 1, i) == Approx(at(0, i)).margin(1e-6)); // last texel repeats the first
        CHECK(at(i, n - 1) == Approx(at(i, 0)).margin(1e-6));
    }
    // Deterministic: the same bytes every time.
    CHECK(foam_scene().textures.at("foam_pattern").rgba == t.rgba);
}

namespace {

// foam=shore composed over a hand-made Surface: varyings p (surface point), t (time), depth. Each
// point becomes a 2x2 quad of lanes `spacing` metres apart in x and z (the pixel footprint the
// pattern filter sees); the result holds lane 0 of each quad.
EvalResult foam_over_surface(const std::vector<double>& points, const std::vector<double>& times,
                             const std::vector<double>& depths, EvalPrecision p, bool relaxed,
                             double spacing = 0.01) {
    Graph g;
    Surface s(g);
    s.surface_point = varying(g, "p", Type::Vec3);
    s.time = varying(g, "t", Type::Float);
    s.depth = varying(g, "depth", Type::Float);
    s.level = constant(g, 0.0);
    s.color = constant(g, {0.0, 0.0, 0.0});
    RelaxedScope shading(g, relaxed);
    compose_choice(s, "foam", "shore");
    g.set_output("out", s.color.id());
    static const SyntheticScene scene = foam_scene();
    EvalInputs in = scene.eval_inputs();
    in.lanes = times.size() * 4;
    for (size_t i = 0; i < times.size(); ++i)
        for (int lane = 0; lane < 4; ++lane) {
            const double dx = (lane & 1) ? spacing : 0.0, dz = (lane & 2) ? spacing : 0.0;
            in.varyings["p"].insert(in.varyings["p"].end(), {points[i * 3] + dx, points[i * 3 + 1],
                                                             points[i * 3 + 2] + dz});
            in.varyings["t"].push_back(times[i]);
            in.varyings["depth"].push_back(depths[i]);
        }
    EvalResult r = evaluate(g, "out", in, p);
    if (!r.ok()) return r;
    std::vector<double> first;
    for (size_t i = 0; i < times.size(); ++i)
        first.insert(first.end(), r.values.begin() + long(i * 12),
                     r.values.begin() + long(i * 12 + 3));
    r.values = first;
    return r;
}

} // namespace

// The pattern is sampled at fract(xz scale + drift t) mapped onto texel centres: it reproduces
// the periodic function, also right at the wrap, where plain fract under clamp-to-edge would
// stretch the last half texel.
TEST_CASE("foam_pattern_sample_reproduces_the_periodic_function_across_the_wrap",
          "[foam][golden]") {
    std::vector<double> points, times, depths, expected;
    for (double x : {-0.0004, 0.0004, 2.5, 9.9996, 10.0004, 37.1})
        for (double z : {-0.0004, 0.0004, 6.3, 19.9996}) {
            points.insert(points.end(), {x, 0.0, z});
            times.push_back(0.0);
            depths.push_back(0.0); // f = 1: the output is the pattern
            auto wrap = [](double v) { return v - std::floor(v); };
            expected.push_back(foam_pattern_value(wrap(0.1 * x), wrap(0.1 * z)));
        }
    const EvalResult r = foam_over_surface(points, times, depths, EvalPrecision::Double, false);
    REQUIRE(r.ok());
    double worst = 0;
    for (size_t i = 0; i < expected.size(); ++i)
        worst = std::max(worst, std::fabs(r.values[i * 3] - expected[i]));
    CHECK(worst < 2e-4); // bilinear interpolation of a 255-texel period (plain fract: 0.01)
}

// Guard: positions up to 1e5 m and times up to 86400 s (water-models.md stress) under half
// precision. The pattern coordinate is geometry and must stay 32-bit; computed in half, 1e5
// overflows to infinity and the pattern is lost.
TEST_CASE("foam_pattern_coordinate_stays_32_bit_under_half_precision", "[foam][guard]") {
    const std::vector<double> points = {1e5 + 3.3, 0.0,  -1e5 + 7.7, 61234.5, 0.0,
                                        4321.25,   -3.0, 0.0,        2.0};
    const std::vector<double> times = {86400.0, 86400.0, 0.0}, depths = {0.0, 0.0, 0.0};
    const EvalResult full = foam_over_surface(points, times, depths, EvalPrecision::Float, true);
    const EvalResult half = foam_over_surface(points, times, depths, EvalPrecision::Half, true);
    REQUIRE(full.ok());
    REQUIRE(half.ok());
    for (size_t i = 0; i < full.values.size(); ++i) {
        CHECK(std::isfinite(half.values[i]));
        CHECK(half.values[i] ==
              Approx(full.values[i]).margin(2e-3)); // pattern <= 1 rounded to binary16: 2^-11
    }
}

// Guard: the texture has one level, so without filtering a pixel spanning metres of water
// samples the pattern at one point: aliasing noise, and far away GPU and CPU positions differ
// by more than a texel (measured 0.015 in a 128x128 render). It fades to its mean from 4 to 2
// pixels per shortest wavelength (2 m at the default 10 m tile).
TEST_CASE("foam_pattern_fades_to_its_mean_as_pixels_outgrow_its_wavelength", "[foam][guard]") {
    const std::vector<double> point = {2.5, 0.0, 6.3}, time = {0.0}, depth = {0.0};
    const double texel =
        foam_over_surface(point, time, depth, EvalPrecision::Double, false, 0.01).values[0];
    REQUIRE(std::fabs(texel - kFoamPatternMean) >
            0.1); // a point where the pattern differs from its mean
    // Footprint 0.5 m = 1/4 wavelength: untouched; 1 m = Nyquist: the mean; 0.75 m: halfway.
    CHECK(foam_over_surface(point, time, depth, EvalPrecision::Double, false, 0.5).values[0] ==
          Approx(texel).margin(0.02));
    CHECK(foam_over_surface(point, time, depth, EvalPrecision::Double, false, 1.0).values[0] ==
          Approx(kFoamPatternMean).epsilon(1e-12));
    CHECK(foam_over_surface(point, time, depth, EvalPrecision::Double, false, 1e6).values[0] ==
          Approx(kFoamPatternMean).epsilon(1e-12));
    const std::vector<NodeInput> in = {{"p", Type::Float}, {"w", Type::Float}};
    const auto halfway = test::eval_node(
        in,
        [](Graph& g, const std::vector<Expr>& v) { return foam_pattern_filtered(g, v[0], v[1]); },
        {1.0, 0.75, 0.2, 0.75, 0.9, 0.0});
    CHECK(halfway[0] == Approx(0.8).epsilon(1e-12));
    CHECK(halfway[1] == Approx(0.4).epsilon(1e-12));
    CHECK(halfway[2] == Approx(0.9).epsilon(1e-12));
}
