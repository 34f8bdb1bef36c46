// The catalog nodes that read textures, through the numeric harness: the probe binds the
// synthetic scene's textures (and linear_clamp) as the fragment pass does, samples level 0 and
// runs ddx / ddy as differences over quads of tuples 4k..4k+3, on lavapipe (GLSL and HLSL
// paths) against the CPU evaluator with the same texels.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "shared_runner.h"
#include "watergen/eval/probe/probe.h"
#include "watergen/eval/probe/probe_table.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/runtime/host_values.h"
#include "watergen/water/node_catalog.h"

using namespace watergen;

namespace {

ProbeRun probe(const std::string& node, Language lang, const std::vector<double>& inputs) {
    return test::checked_probe(probe_graph(*find_catalog_node(node)), lang, inputs, {},
                               probe_scene_textures());
}

// (x, z, t): a grid over |xz| <= 60 m (several 16.7 m tiles of the height map) and t <= 50 s,
// off the texel grid.
std::vector<double> xz_t_tuples() {
    std::vector<double> v;
    const int n = 24;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            v.insert(v.end(), {-60.0 + 120.0 * i / (n - 1) + 0.0137 * j,
                               -60.0 + 120.0 * j / (n - 1) - 0.0071 * i,
                               50.0 * ((i * 7 + j * 3) % n) / (n - 1)});
    return v;
}

// (eye, view_ray, level, time): the synthetic camera's rays over the water, from the horizon
// down to the near field, eye 5 m up.
std::vector<double> eye_ray_tuples() {
    std::vector<double> v;
    for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j) {
            const double x = -0.6 + 1.2 * j / 15, y = -0.02 - 0.9 * i / 15, z = 1.0;
            const double len = std::sqrt(x * x + y * y + z * z);
            v.insert(v.end(), {0.0, 5.0, -7.0, x / len, y / len, z / len, 0.0, 1.5 * j});
        }
    return v;
}

// (base, position, time) in 2x2 quads: pixel (i, j) of quad q sits at p_q + i dx + j dy on the
// water plane, with footprints dx, dy from 2 cm (near) to 0.4 m (far, where the detail fades).
std::vector<double> detail_quad_tuples() {
    std::vector<double> v;
    for (int q = 0; q < 128; ++q) {
        const double far = (q % 16) / 15.0;
        const double step = 0.02 + 0.38 * far;
        const double px = -20.0 + 0.731 * q, pz = 3.0 + 60.0 * far;
        const double base[3] = {0.05 * std::sin(q), 1.0,
                                0.05 * std::cos(q)}; // not unit: normalised by the node
        for (int k = 0; k < 4; ++k) {
            const double x = px + step * (k & 1) + 0.1 * step * (k >> 1);
            const double z = pz + 1.7 * step * (k >> 1);
            v.insert(v.end(), {base[0], base[1], base[2], x, 0.0, z, 0.25 * q});
        }
    }
    return v;
}

// (color, xz): one colour over a grid across the caustics window (-5..5 m), past its edges and
// over several caustics tiles, off the texel grid.
std::vector<double> color_xz_tuples() {
    std::vector<double> v;
    const int n = 24;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            v.insert(v.end(), {0.8, 0.5, 0.25, -7.3 + 14.6 * i / (n - 1) + 0.0113 * j,
                               -7.3 + 14.6 * j / (n - 1) - 0.0059 * i});
    return v;
}

double max_gap(const std::vector<double>& a, const std::vector<double>& b) {
    double m = 0;
    for (size_t i = 0; i < a.size(); ++i)
        m = std::max(m, std::fabs(a[i] - b[i]));
    return m;
}

struct TexturedCase {
    const char* node;
    std::vector<double> (*tuples)();
    double tolerance; // on max |gpu - cpu float|
};

} // namespace

TEST_CASE("every_catalog_node_that_reads_a_texture_is_probed_here", "[probe][textures]") {
    std::set<std::string> textured;
    for (const auto& node : node_catalog())
        if (!probe_graph(node).textures().empty()) textured.insert(node.name);
    CHECK(textured == std::set<std::string>{"caustics.area_ratio", "caustics.photon_splat",
                                            "caustics.texture", "normals.detail_map",
                                            "normals.heightmap_diff", "scene_input.depth_buffer",
                                            "waves.heightmap.height", "waves.heightmap_march",
                                            "waves.heightmap_march_converged"});
}

TEST_CASE("the_depth_buffer_node_unprojects_to_the_scene_positions", "[probe][textures]") {
    // At texel centres of the 64x64 scene, with its eye and inverse view-projection (default
    // conventions: reversed Z, NDC z 0..1), the node returns the eye plus the scene_position
    // texel: the depth buffer is those points projected in double and rounded to float.
    const SyntheticScene scene = make_synthetic_scene(64, 64);
    const TextureData& position = scene.textures.at("scene_position");
    // The node works in the shader's frame (host_values.h): its eye input and its result are
    // relative to the frame centre.
    std::vector<double> eye = scene.uniforms.at("eye_position");
    const FrameCentre centre = frame_centre_of(eye[0], eye[2]);
    eye[0] -= centre.x;
    eye[2] -= centre.z;
    std::vector<double> tuples, expected;
    for (uint32_t y = 0; y < 64; y += 3)
        for (uint32_t x = 0; x < 64; x += 3) {
            tuples.insert(tuples.end(), {(x + 0.5) / 64, (y + 0.5) / 64, eye[0], eye[1], eye[2]});
            for (int k = 0; k < 3; ++k)
                expected.push_back(eye[size_t(k)] + position.rgba[(size_t(y) * 64 + x) * 4 + k]);
        }
    for (Language lang : {Language::Glsl, Language::Hlsl}) {
        INFO(to_string(lang));
        const ProbeRun run =
            test::checked_probe(probe_graph(*find_catalog_node("scene_input.depth_buffer")), lang,
                                tuples, scene.uniforms, probe_scene_textures());
        REQUIRE(run.gpu.size() == expected.size());
        double off = 0, apart = 0;
        for (size_t i = 0; i < expected.size(); ++i) {
            // Relative to the point's distance from the eye (up to 1000 m for the sky).
            const size_t t = i / 3;
            double d2 = 0;
            for (int k = 0; k < 3; ++k)
                d2 += (expected[t * 3 + k] - eye[k]) * (expected[t * 3 + k] - eye[k]);
            off = std::max(off, std::fabs(run.gpu[i] - expected[i]) / std::sqrt(d2));
            apart = std::max(apart, std::fabs(run.gpu[i] - run.cpu_float[i]) / std::sqrt(d2));
        }
        std::printf("scene_input.depth_buffer %s: %zu texels, max |gpu - texel| / distance %.3g, "
                    "max |gpu - cpu float| / distance %.3g\n",
                    to_string(lang), expected.size() / 3, off, apart);
        // A few float ulps of the distance: the depth's rounding (2^-24 relative in reversed
        // Z), the unprojection's and the texel's own.
        // Measured 8.9e-7 and 6.1e-8 (GLSL and HLSL alike).
        CHECK(off <= 2e-6);
        CHECK(apart <= 2e-7);
    }
}

TEST_CASE("textured_nodes_agree_between_gpu_and_cpu_float", "[probe][textures]") {
    // lavapipe filters RGBA32F with float weights (runner_compute_test: within half an ulp of
    // the exact weight; 8-bit sub-texel weights would be up to 1/512 of a texel step off, 7e-4
    // of height here), as the CPU evaluator does in double. Measured max |GPU - CPU float|, the
    // same on both paths: height 3.0e-8 and heightmap_diff normal 1.2e-7 (an ulp or two of the
    // sampled values), detail normal 1.8e-7; the marches 1.9e-6 and 3.8e-6, one float ulp of a
    // hit point or distance between 32 and 64 m (the CPU float is 3.6e-5 from double there).
    const TexturedCase cases[] = {
        {"waves.heightmap.height", &xz_t_tuples, 1e-7},
        {"normals.heightmap_diff", &xz_t_tuples, 3e-7},
        {"waves.heightmap_march", &eye_ray_tuples, 4e-6},
        {"waves.heightmap_march_converged", &eye_ray_tuples, 4e-6},
        {"normals.detail_map", &detail_quad_tuples, 3e-7},
        {"caustics.texture", &color_xz_tuples, 3e-7},
        {"caustics.area_ratio", &color_xz_tuples, 3e-7},
        {"caustics.photon_splat", &color_xz_tuples, 3e-7},
    };
    for (const auto& c : cases)
        for (Language lang : {Language::Glsl, Language::Hlsl}) {
            INFO(c.node << " " << to_string(lang));
            const ProbeRun run = probe(c.node, lang, c.tuples());
            const ProbeSummary s = summarize_probe(run);
            std::printf("%-32s %s  %zu tuples  max|gpu - cpu float| %.3g  max|cpu float - cpu "
                        "double| %.3g\n",
                        c.node, to_string(lang), run.tuples, s.max_gpu_vs_cpu_float,
                        max_gap(run.cpu_float, run.cpu_double));
            CHECK(s.gpu.non_finite() == 0);
            CHECK(s.cpu_float.non_finite() == 0);
            CHECK(max_gap(run.gpu, run.cpu_float) <= c.tolerance);
            // The texels matter: the outputs vary over the tuples by far more than the tolerance.
            const auto [lo, hi] = std::minmax_element(run.gpu.begin(), run.gpu.end());
            CHECK(*hi - *lo > 0.05);
            if (std::string(c.node) == "normals.detail_map") {
                // ... and the detail map tilts the base normal (by up to ~0.5 where it has not
                // faded).
                const std::vector<double> in = c.tuples();
                double tilt = 0;
                for (size_t t = 0; t < run.tuples; ++t) {
                    const double* b = &in[t * 7];
                    const double len = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
                    for (int k = 0; k < 3; ++k)
                        tilt = std::max(tilt, std::fabs(run.gpu[t * 3 + k] - b[k] / len));
                }
                CHECK(tilt > 0.2);
            }
        }
}

TEST_CASE("probe_derivatives_are_fine_differences_over_quads_of_tuples", "[probe][textures]") {
    // ddx pairs tuples (4k, 4k+1) and (4k+2, 4k+3), ddy pairs (4k, 4k+2) and (4k+1, 4k+3), on
    // both sides. Small integers: every difference is exact in float.
    Graph g;
    Expr p = varying(g, "p", Type::Vec2);
    g.set_output("dx", ddx(p * p.x()).id());
    g.set_output("dy", ddy(p.y() * 3.0).id());
    const std::vector<double> in = {1, 2, 4, 3, 2, 7, 5, 11, -3, 1, 6, -2, 8, 8, 2, -4};
    // Per tuple: dx.x, dx.y, dy.
    const std::vector<double> expected = {15, 10, 15, 15, 10, 24, 21,  41,  15, 21,  41,  24,
                                          27, -9, 21, 27, -9, -6, -60, -72, 21, -60, -72, -6};
    for (Language lang : {Language::Glsl, Language::Hlsl}) {
        INFO(to_string(lang));
        const ProbeRun run = test::checked_probe(g, lang, in);
        CHECK(run.gpu == expected);
        CHECK(run.cpu_float == expected);
    }
    // An incomplete quad has no well-defined neighbours on the GPU: refused.
    const ProbeRun partial = run_probe(test::shared_runner(), g, Language::Glsl,
                                       std::vector<double>(in.begin(), in.end() - 2));
    CHECK(partial.error ==
          "the graph takes ddx / ddy over quads of tuples 4k..4k+3; 7 tuples are not whole quads");
}

TEST_CASE("a_probe_without_the_texture_its_node_reads_fails_naming_it", "[probe][textures]") {
    const ProbeRun run =
        run_probe(test::shared_runner(), probe_graph(*find_catalog_node("waves.heightmap.height")),
                  Language::Glsl, {1.0, 2.0, 0.0});
    CHECK(run.error == "the graph reads texture 'height_map'; none supplied");
}
