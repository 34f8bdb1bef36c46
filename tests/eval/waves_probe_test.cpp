// The texture-free wave nodes through the numeric harness: compute shaders on lavapipe (GLSL
// and HLSL paths) against the CPU evaluator, and the stress ranges of water-models.md.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "shared_runner.h"
#include "watergen/eval/probe/probe.h"
#include "watergen/runtime/host_values.h"
#include "watergen/water/mesh_shader.h"
#include "waves_support.h"

using namespace watergen;

namespace {

ProbeRun probe(const Graph& g, Language lang, const std::vector<double>& inputs,
               const test::Uniforms& uniforms = {}) {
    ProbeRun run = run_probe(test::shared_runner(), g, lang, inputs, uniforms);
    for (const auto& d : run.diagnostics)
        UNSCOPED_INFO(format_diagnostic(d));
    INFO(run.error);
    REQUIRE(run.ok());
    CHECK(run.validation_messages.empty());
    return run;
}

ProbeRun probe(const std::string& node, Language lang, const std::vector<double>& inputs,
               const test::Uniforms& uniforms = {}) {
    return probe(probe_graph(*find_catalog_node(node)), lang, inputs, uniforms);
}

double max_gap(const std::vector<double>& a, const std::vector<double>& b) {
    double m = 0;
    for (size_t i = 0; i < a.size(); ++i)
        m = std::max(m, std::fabs(a[i] - b[i]));
    return m;
}

// (x, z, t) tuples: a grid over |xz| <= `extent` m and t in [0, `duration`] s.
std::vector<double> xz_t_tuples(double extent, double duration, int n) {
    std::vector<double> v;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double x = extent * (2.0 * i / (n - 1) - 1.0) + 0.137 * j;
            const double z = extent * (2.0 * j / (n - 1) - 1.0) - 0.071 * i;
            v.insert(v.end(), {x, z, duration * ((i * 7 + j * 3) % n) / (n - 1)});
        }
    return v;
}

const char* const kXzNodes[] = {"waves.sum_of_sines.height", "waves.sum_of_sines.slope",
                                "waves.sum_of_sines.normal", "waves.gerstner.displacement",
                                "waves.gerstner.normal",     "waves.gerstner.normal_gpugems"};

} // namespace

TEST_CASE("wave_functions_agree_between_gpu_and_cpu_float", "[probe][waves]") {
    // Within 100 m and 100 s the phases stay under ~500 rad. Measured max |GPU - CPU float|,
    // identical on both paths: 3.9e-6 (sum-of-sines height), 3.7e-6 (slope), 3.5e-6 (normal),
    // 4.6e-6 (Gerstner displacement), 4.5e-6 (exact normal), 5.5e-6 (GPU Gems normal); the CPU
    // float is itself 7e-6 to 1.2e-5 from double. Most of it is the phase: lavapipe contracts
    // f (d . p) + t phi into fused multiply-adds (one rounding fewer than the CPU's), and a
    // float ulp of a 500 rad phase is 3e-5 rad.
    const std::vector<double> in = xz_t_tuples(100.0, 100.0, 24);
    for (const char* node : kXzNodes)
        for (Language lang : {Language::Glsl, Language::Hlsl}) {
            INFO(node << " " << to_string(lang));
            const ProbeRun run = probe(node, lang, in);
            const double gap = max_gap(run.gpu, run.cpu_float);
            std::printf("%-30s %s  max|gpu - cpu float| %.3g  max|cpu float - cpu double| %.3g\n",
                        node, to_string(lang), gap, max_gap(run.cpu_float, run.cpu_double));
            CHECK(gap <= 1e-5);
        }
}

TEST_CASE("wave_functions_stay_finite_at_a_day_and_100_km", "[probe][waves][stress]") {
    // water-models.md: time up to 86400 s and positions up to 1e5 m, under half precision
    // too. The wave nodes keep 32-bit floats in half mode (FullPrecisionScope), so cpu_half
    // equals cpu_float. Phases reach ~3e5 rad, where a float ulp is 0.03 rad: GPU and CPU
    // both take the sine of an argument whose low bits are rounding noise (and lavapipe's
    // fused multiply-adds round the phase differently). Measured max |GPU - CPU float| there:
    // 1.2e-3 (sum-of-sines height, m) to 2.6e-3 (Gerstner displacement, m), against 4e-6
    // within 100 m and 100 s; only finiteness and unit normals are asserted.
    std::vector<double> in;
    for (double x : {-1e5, -3e4, 0.0, 1234.5, 1e5})
        for (double z : {-1e5, 0.0, 7e4, 1e5})
            for (double t : {0.0, 3600.0, 86399.5, 86400.0})
                in.insert(in.end(), {x, z, t});
    for (const char* node : kXzNodes)
        for (Language lang : {Language::Glsl, Language::Hlsl}) {
            INFO(node << " " << to_string(lang));
            const ProbeRun run = probe(node, lang, in);
            std::printf("%-30s %s  far field: max|gpu - cpu float| %.3g\n", node, to_string(lang),
                        max_gap(run.gpu, run.cpu_float));
            for (const auto* values : {&run.gpu, &run.cpu_double, &run.cpu_float, &run.cpu_half})
                for (double v : *values)
                    CHECK(std::isfinite(v));
            CHECK(run.cpu_half == run.cpu_float);
            if (std::string(node).find("normal") != std::string::npos)
                for (size_t t = 0; t < run.tuples; ++t) {
                    const double* n = &run.gpu[t * 3];
                    CHECK(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) ==
                          Approx(1.0).margin(1e-5));
                    CHECK(n[1] > 0.0);
                }
        }
}

TEST_CASE("surface_search_survives_horizontal_and_vertical_eye_rays_on_the_gpu",
          "[probe][waves][stress]") {
    // water-models.md: eye ray y in {0, +-1e-7, +-1e-3}. Eye above, on and below the water.
    std::vector<double> in;
    for (double eye_y : {5.0, 0.0, -2.0})
        for (double y : {0.0, 1e-7, -1e-7, 1e-3, -1e-3, -1.0})
            for (double t : {0.0, 86400.0}) {
                const double xz = std::sqrt(std::max(0.0, 1.0 - y * y));
                in.insert(in.end(), {0.0, eye_y, -7.0, 0.6 * xz, y, 0.8 * xz, 0.0, t});
            }
    for (const char* node : {"waves.flat", "waves.sum_of_sines", "waves.gerstner"})
        for (Language lang : {Language::Glsl, Language::Hlsl}) {
            INFO(node << " " << to_string(lang));
            const ProbeRun run = probe(node, lang, in);
            for (const auto* values : {&run.gpu, &run.cpu_double, &run.cpu_float, &run.cpu_half})
                for (double v : *values)
                    CHECK(std::isfinite(v));
            // Straight down from 5 m: the point is on the surface, 5 m +- the waves below.
            const double* down = &run.gpu[(0 * 12 + 5 * 2) * 4];
            CHECK(down[3] == Approx(5.0).margin(0.5));
        }
}

TEST_CASE("gerstner_amplitude_zero_is_a_flat_still_surface_on_the_gpu", "[probe][waves][stress]") {
    // Q_i = Q / (w_i A_i n) is inf at A = 0, and Q_i A_i = inf * 0 = NaN without the guard.
    const std::vector<double> in = xz_t_tuples(50.0, 86400.0, 6);
    for (Language lang : {Language::Glsl, Language::Hlsl}) {
        const ProbeRun d =
            probe("waves.gerstner.displacement", lang, in, {{"gerstner_amplitude", {0.0}}});
        for (double v : d.gpu)
            CHECK(v == 0.0);
        for (const char* node : {"waves.gerstner.normal", "waves.gerstner.normal_gpugems"}) {
            const ProbeRun n = probe(node, lang, in, {{"gerstner_amplitude", {0.0}}});
            for (size_t t = 0; t < n.tuples; ++t) {
                CHECK(n.gpu[t * 3 + 0] == 0.0);
                CHECK(n.gpu[t * 3 + 1] == 1.0);
                CHECK(n.gpu[t * 3 + 2] == 0.0);
            }
        }
    }
}

TEST_CASE("mesh_vertex_stage_math_agrees_between_gpu_and_cpu", "[probe][waves][mesh]") {
    // The mesh geometry's vertex graph itself, run as a compute shader over grid points with
    // their level attributes: the morph, clip position, displaced point and grid point against
    // the CPU evaluator in float. Odd points morph by -h along x; the morph range puts the
    // points near the eye at t = 0, the far ones at t = 1 and a band between.
    std::vector<double> grid;
    for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i)
            grid.insert(grid.end(), {-14.0 + 28.0 * i / 15, -4.0 + 34.0 * j / 15,
                                     i % 2 ? -0.5 : 0.0, 0.0, 0.5});
    const test::Uniforms camera = {{"eye_position", {0.0, 5.0, -7.0}},
                                   {"mesh_camera_forward", {0.0, -0.4695, 0.8829}},
                                   {"mesh_camera_up", {0.0, 0.8829, 0.4695}},
                                   {"mesh_projection", {1.732, 1.732}},
                                   {"grid_morph_start", {20.0}},
                                   {"grid_morph_end", {40.0}}};
    for (const char* model : {"sum_of_sines", "gerstner"})
        for (Language lang : {Language::Glsl, Language::Hlsl}) {
            const MeshStages mesh = build_mesh_stages("mesh", model);
            const ProbeRun run = probe(mesh.vertex, lang, grid, camera);
            REQUIRE(run.layout.output_stride == 13); // position 4, world 3, grid 2, clip 4
            std::printf("mesh %-13s %s vertex stage: max|gpu - cpu float| %.3g\n", model,
                        to_string(lang), max_gap(run.gpu, run.cpu_float));
            // Clip coordinates up to ~40: a few float ulps of 40.
            CHECK(max_gap(run.gpu, run.cpu_float) <= 2e-5);
            // The morphed grid point: t = clamp((d / 0.5 - 20) / 20, 0, 1), d = |x - e.x| or
            // |z - e.z| for the eye e in the frame the grid points are in: (-0.5, -0.5) about
            // the centre (0.5, -6.5) of the eye's whole-metre cell (host_values.h).
            const FrameCentre c = frame_centre_of(0.0, -7.0);
            REQUIRE(c == FrameCentre{0.5, -6.5});
            for (size_t t = 0; t < run.tuples; ++t) {
                const double x = grid[t * 5], z = grid[t * 5 + 1], dx = grid[t * 5 + 2];
                const double d =
                    std::max(std::abs(x - (0.0 - c.x)), std::abs(z - (-7.0 - c.z))) / 0.5;
                const double morph = std::clamp((d - 20.0) / 20.0, 0.0, 1.0);
                CHECK(run.cpu_float[t * 13 + 7] == Approx(x + dx * morph).margin(1e-5));
                CHECK(run.gpu[t * 13 + 8] == Approx(z).margin(1e-5));
            }
        }
}

TEST_CASE("a_wave_count_from_data_agrees_between_gpu_and_cpu_float", "[probe][waves]") {
    // The loop over the waves runs as many as the uniform says: none (a flat, still surface),
    // two, or all eight (waves 4..7 at their defaults); the same bound as the default four.
    const std::vector<double> in = xz_t_tuples(100.0, 100.0, 12);
    for (double count : {0.0, 2.0, 8.0})
        for (const std::string family : {"waves", "gerstner"})
            for (Language lang : {Language::Glsl, Language::Hlsl}) {
                const std::string node =
                    family == "waves" ? "waves.sum_of_sines.slope" : "waves.gerstner.normal";
                INFO(node << " " << to_string(lang) << " count " << count);
                const ProbeRun run = probe(node, lang, in, {{family + "_wave_count", {count}}});
                const double gap = max_gap(run.gpu, run.cpu_float);
                std::printf("%-26s %s  %g waves: max|gpu - cpu float| %.3g\n", node.c_str(),
                            to_string(lang), count, gap);
                CHECK(gap <= 1e-5);
                const std::vector<double> flat = family == "waves"
                                                     ? std::vector<double>{0.0, 0.0}
                                                     : std::vector<double>{0.0, 1.0, 0.0};
                for (size_t t = 0; count == 0 && t < run.tuples; ++t)
                    for (size_t c = 0; c < flat.size(); ++c)
                        CHECK(run.gpu[t * flat.size() + c] == flat[c]);
            }
}
