// The sampling-free reflection and refraction nodes through the numeric harness: lavapipe
// (GLSL and HLSL paths) and the CPU in double, float and half over water-models.md's stress
// ranges. Every output is finite and in its documented range; GPU and CPU float agree.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "shared_runner.h"
#include "watergen/eval/probe/probe.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/water/node_catalog.h"

using namespace watergen;

namespace {

using Uniforms = std::map<std::string, std::vector<double>>;

ProbeRun probe(const std::string& node, Language lang, const std::vector<double>& inputs,
               const Uniforms& uniforms = {}) {
    const CatalogNode* n = find_catalog_node(node);
    REQUIRE(n != nullptr);
    const Graph g = probe_graph(*n);
    ProbeRun run = run_probe(test::shared_runner(), g, lang, inputs, uniforms);
    for (const auto& d : run.diagnostics)
        UNSCOPED_INFO(format_diagnostic(d));
    INFO(run.error);
    REQUIRE(run.ok());
    for (const auto& m : run.validation_messages)
        UNSCOPED_INFO(m);
    CHECK(run.validation_messages.empty());
    return run;
}

// water-models.md: depth and acc stress set.
const std::vector<double> kDepths = {-1e-3, 0, 1e-6, 0.1, 10, 21.1, 190, 1e3, 1e4, 1e30, INFINITY};

std::vector<std::vector<double>> unit_rays() {
    const double s = std::sqrt(0.5);
    return {{0, -1, 0},    {0, 1, 0},  {1, 0, 0},          {0, -1e-7, 1},         {0, 1e-7, 1},
            {0, -1e-3, 1}, {s, -s, 0}, {0.6, -0.48, 0.64}, {-0.3, 0.2, -0.932738}};
}

std::vector<std::vector<double>> normals() {
    const double s = std::sqrt(0.5);
    return {{0, 1, 0}, {0.1, 0.98995, 0.1}, {s, s, 0}, {1, 0, 0}, {0, -1, 0}};
}

void append(std::vector<double>& out, const std::vector<double>& v) {
    out.insert(out.end(), v.begin(), v.end());
}

// Largest |GPU - CPU float| over the lanes `use` accepts, each scaled by max(1, |CPU|).
template <class Use> double worst_gpu_vs_cpu(const ProbeRun& run, Use use) {
    double worst = 0;
    const size_t stride = run.layout.output_stride;
    for (size_t t = 0; t < run.tuples; ++t)
        for (size_t c = 0; c < stride; ++c) {
            if (!use(t, c)) continue;
            const double cpu = run.cpu_float[t * stride + c];
            worst = std::max(worst, std::fabs(run.gpu[t * stride + c] - cpu) /
                                        std::max(1.0, std::fabs(cpu)));
        }
    return worst;
}

void check_finite(const ProbeRun& run) {
    for (const auto* values : {&run.gpu, &run.cpu_double, &run.cpu_float, &run.cpu_half})
        for (double v : *values)
            CHECK(std::isfinite(v));
}

const auto kAll = [](size_t, size_t) { return true; };

} // namespace

TEST_CASE("sky_lookup_is_finite_in_the_upper_hemisphere_with_a_unit_weight",
          "[probe][stress][reflection]") {
    std::vector<double> in;
    auto rays = unit_rays();
    rays.push_back({0, 0, 0});
    for (const auto& v : rays)
        for (const auto& n : normals()) {
            append(in, v);
            append(in, n);
        }
    for (Language lang : {Language::Glsl, Language::Hlsl}) {
        INFO(to_string(lang));
        const ProbeRun run = probe("reflection.sky_lookup", lang, in);
        check_finite(run);
        for (const auto* values : {&run.gpu, &run.cpu_double, &run.cpu_float, &run.cpu_half})
            for (size_t t = 0; t < run.tuples; ++t) {
                CHECK((*values)[t * 4 + 1] >= 0.0); // never the lower half of the cube
                CHECK((*values)[t * 4 + 3] >= 0.0);
                CHECK((*values)[t * 4 + 3] <= 1.0);
            }
        // reflect, abs and smoothstep: a few float ulps.
        const double worst = worst_gpu_vs_cpu(run, kAll);
        std::printf("reflection.sky_lookup %s: max |gpu - cpu float| %.3g\n", to_string(lang),
                    worst);
        CHECK(worst <= 1e-6);
    }
}

TEST_CASE("projective_uv_is_finite_and_on_the_texture_for_far_near_and_behind_points",
          "[probe][stress][reflection]") {
    // The scene's matrices; points up to 1e5 m (half precision must not touch them), the eye
    // itself (q.w = 0 up to rounding) and points behind the camera.
    const SyntheticScene scene = make_synthetic_scene(128, 128);
    std::vector<double> in;
    const std::vector<std::vector<double>> points = {
        {0, 0, 0},        {1e5, 0, 1e5}, {-1e5, 0, 1e5},  {0, 0, -1e5},  {0, 5, -7},
        {0, 5, -6.99999}, {3, 0, -20},   {2.5, -0.2, 14}, {1e5, 3, -1e5}};
    for (const auto& p : points)
        for (const auto& n : normals()) {
            append(in, p);
            append(in, n);
        }
    for (Language lang : {Language::Glsl, Language::Hlsl}) {
        INFO(to_string(lang));
        const ProbeRun run = probe("reflection.projective_uv", lang, in, scene.uniforms);
        check_finite(run);
        for (const auto* values : {&run.gpu, &run.cpu_double, &run.cpu_float, &run.cpu_half})
            for (size_t t = 0; t < run.tuples; ++t) {
                for (int c = 0; c < 2; ++c) {
                    CHECK((*values)[t * 3 + c] >= 0.0);
                    CHECK((*values)[t * 3 + c] <= 1.0);
                }
                const double valid = (*values)[t * 3 + 2];
                CHECK((valid == 0.0 || valid == 1.0));
            }
        // The flag agrees everywhere but at the eye itself, where q.w is rounding noise around 0.
        for (size_t t = 0; t < run.tuples; ++t)
            if (std::fabs(in[t * 6 + 2] + 7) > 1e-3)
                CHECK(run.gpu[t * 3 + 2] == run.cpu_float[t * 3 + 2]);
        // Half precision rounds the shading around it, not the projection: points of 1e5 m
        // would overflow binary16 (uv from inf / inf) without the full-precision scope.
        for (size_t t = 0; t < run.tuples; ++t) {
            INFO("tuple " << t);
            CHECK(run.cpu_half[t * 3 + 2] == run.cpu_float[t * 3 + 2]);
            if (run.cpu_float[t * 3 + 2] == 1.0)
                for (int c = 0; c < 2; ++c)
                    CHECK(run.cpu_half[t * 3 + c] == Approx(run.cpu_float[t * 3 + c]).margin(1e-3));
        }
        const double worst = worst_gpu_vs_cpu(
            run, [&](size_t t, size_t) { return run.gpu[t * 3 + 2] == run.cpu_float[t * 3 + 2]; });
        std::printf("reflection.projective_uv %s: max |gpu - cpu float| %.3g\n", to_string(lang),
                    worst);
        CHECK(worst <= 1e-6);
    }
}

TEST_CASE("projective_uv_flags_the_stress_w_values_on_the_gpu", "[probe][stress][reflection]") {
    // water-models.md: projective w in {-1, -1e-6, 0, 1e-6}; with q.x = 0 the unguarded
    // divide is 0 / 0.
    for (double qx : {0.3, 0.0})
        for (double w : {-1.0, -1e-6, 0.0, 1e-6}) {
            INFO("q.x " << qx << " w " << w);
            const Uniforms m = {{"reflection_view_proj_c0", {0, 0, 0, 0}},
                                {"reflection_view_proj_c1", {0, 0, 0, 0}},
                                {"reflection_view_proj_c2", {0, 0, 0, 0}},
                                {"reflection_view_proj_c3", {qx, 0.2, 0, w}}};
            for (Language lang : {Language::Glsl, Language::Hlsl}) {
                const ProbeRun run = probe("reflection.projective_uv", lang, {5, 0, 5, 0, 1, 0}, m);
                check_finite(run);
                CHECK(run.gpu[2] == 0.0);
                CHECK(run.gpu[0] == 0.5);
                CHECK(run.gpu[1] == 0.5);
            }
        }
}

TEST_CASE("fourier_nodes_are_finite_for_vertical_tiny_and_zero_rays",
          "[probe][stress][reflection]") {
    const std::vector<std::vector<double>> coefs = {
        {0, 0, 0, 0, 0, 0, 0, 0},
        {0.08, 0.03, -0.05, 0.02, 0.015, -0.01, 0.007, 0.004},
        {10, -10, 10, -10, 10, -10, 10, -10}};
    auto rays = unit_rays();
    for (const auto& r : std::vector<std::vector<double>>{
             {0, 0, 0}, {1e-20, 1, 1e-20}, {1e-7, -1, 0}, {0, -1, 1e-7}})
        rays.push_back(r);
    std::vector<double> in;
    for (const auto& c : coefs)
        for (const auto& r : rays) {
            append(in, c);
            append(in, r);
        }
    for (Language lang : {Language::Glsl, Language::Hlsl}) {
        INFO(to_string(lang));
        const ProbeRun series = probe("reflection.fourier_series", lang, in);
        check_finite(series);
        // The series is a polynomial in a unit (x, y): |value| <= sum |coefficients|.
        for (size_t t = 0; t < series.tuples; ++t)
            CHECK(std::fabs(series.gpu[t]) <= 80.0 + 1e-3);
        const double worst_series = worst_gpu_vs_cpu(series, kAll);
        const ProbeRun weight = probe("reflection.fourier_sky_weight", lang, in);
        check_finite(weight);
        for (const auto* values :
             {&weight.gpu, &weight.cpu_double, &weight.cpu_float, &weight.cpu_half})
            for (double v : *values) {
                CHECK(v >= 0.0);
                CHECK(v <= 1.0);
            }
        const double worst_weight = worst_gpu_vs_cpu(weight, kAll);
        // The colour lies between fourier_below_color and sky_color, component by component.
        const ProbeRun color = probe("reflection.fourier_horizon", lang, in);
        check_finite(color);
        const double dark[3] = {0.05, 0.07, 0.06}, sky[3] = {0.55, 0.7, 0.9};
        for (const auto* values :
             {&color.gpu, &color.cpu_double, &color.cpu_float, &color.cpu_half})
            for (size_t t = 0; t < color.tuples; ++t)
                for (int c = 0; c < 3; ++c) {
                    CHECK((*values)[t * 3 + c] >= dark[c] - 1e-3);
                    CHECK((*values)[t * 3 + c] <= sky[c] + 1e-3);
                }
        std::printf("reflection.fourier_series %s: %.3g, fourier_sky_weight: %.3g (max |gpu - cpu "
                    "float|, relative above 1)\n",
                    to_string(lang), worst_series, worst_weight);
        // Measured 1.9e-7 and 3e-8. Polynomials of degree 4 in rsqrt-normalised components; the
        // weight is a smoothstep of a difference that cancels near the horizon, where an input
        // ulp moves it by up to 15x (the default transition's slope): headroom for that.
        CHECK(worst_series <= 2e-6);
        CHECK(worst_weight <= 1e-5);
    }
}

TEST_CASE("screen_distort_uv_stays_on_the_screen_at_every_stress_depth",
          "[probe][stress][refraction]") {
    std::vector<double> in;
    for (double d : kDepths)
        for (const auto& uv : std::vector<std::vector<double>>{{0, 0}, {0.5, 0.5}, {1, 1}})
            for (const auto& n : normals()) {
                append(in, uv);
                append(in, n);
                in.push_back(d);
            }
    for (double fade : {1.0, 0.0})
        for (Language lang : {Language::Glsl, Language::Hlsl}) {
            INFO(to_string(lang) << " fade depth " << fade);
            const ProbeRun run = probe("refraction.screen_distort_uv", lang, in,
                                       {{"refraction_shore_fade_depth", {fade}}});
            check_finite(run);
            for (const auto* values : {&run.gpu, &run.cpu_double, &run.cpu_float, &run.cpu_half})
                for (double v : *values) {
                    CHECK(v >= 0.0);
                    CHECK(v <= 1.0);
                }
            const double worst = worst_gpu_vs_cpu(run, kAll);
            std::printf("refraction.screen_distort_uv %s fade %g: max |gpu - cpu float| %.3g\n",
                        to_string(lang), fade, worst);
            CHECK(worst <= 1e-6);
        }
}

TEST_CASE("refracted_ray_is_finite_and_on_the_screen_at_every_stress_depth",
          "[probe][stress][refraction]") {
    const SyntheticScene scene = make_synthetic_scene(128, 128);
    const std::vector<std::vector<double>> points = {
        {0, 0, 0}, {2.5, 0, 14}, {1e5, 0, 1e5}, {0, 0, -6.5}, {0, 5, -7}};
    std::vector<double> point_in, uv_in;
    for (const auto& p : points)
        for (const auto& v : unit_rays())
            for (const auto& n : normals())
                for (double d : kDepths) {
                    append(point_in, p);
                    append(point_in, v);
                    append(point_in, n);
                    point_in.push_back(d);
                    uv_in.insert(uv_in.end(), {0.25, 0.75});
                    append(uv_in, p);
                    append(uv_in, v);
                    append(uv_in, n);
                    uv_in.push_back(d);
                }
    for (bool tir : {false, true}) {
        Uniforms uniforms = scene.uniforms;
        if (tir)
            uniforms["ior_air"] = {1.33333}, uniforms["ior_water"] = {1.0}; // from under the water
        for (Language lang : {Language::Glsl, Language::Hlsl}) {
            INFO(to_string(lang) << (tir ? " from below" : " from above"));
            const ProbeRun w = probe("refraction.refracted_ray_point", lang, point_in, uniforms);
            check_finite(w);
            // W lies within dv_max / 3 of U (refract() gives a unit or zero vector).
            for (size_t t = 0; t < w.tuples; ++t) {
                double dist2 = 0;
                for (size_t c = 0; c < 3; ++c)
                    dist2 += std::pow(w.gpu[t * 3 + c] - point_in[t * 10 + c], 2);
                CHECK(std::sqrt(dist2) <=
                      2.0 / 3.0 * (1 + 1e-5) + 1e-2 * (std::fabs(point_in[t * 10]) > 1e4));
            }
            const double worst_w = worst_gpu_vs_cpu(w, kAll);
            const ProbeRun uv = probe("refraction.refracted_ray_uv", lang, uv_in, uniforms);
            check_finite(uv);
            for (const auto* values : {&uv.gpu, &uv.cpu_double, &uv.cpu_float, &uv.cpu_half})
                for (double v : *values) {
                    CHECK(v >= 0.0);
                    CHECK(v <= 1.0);
                }
            const double worst_uv = worst_gpu_vs_cpu(uv, kAll);
            std::printf("refraction.refracted_ray_point %s%s: %.3g, refracted_ray_uv: %.3g (max "
                        "|gpu - cpu float|)\n",
                        to_string(lang), tir ? " (from below)" : "", worst_w, worst_uv);
            // Measured <= 1.2e-7 (relative above 1) for both.
            CHECK(worst_w <= 1e-6);
            CHECK(worst_uv <= 1e-6);
        }
    }
}
