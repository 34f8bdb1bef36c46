// The CPU evaluator's cube maps against hand-computed texels: Vulkan's face selection and
// per-face coordinates, texel centres, seamless linear filtering across edges and corners (as
// lavapipe does it; optics_render_test.cpp compares with lavapipe itself), nearest clamping.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "watergen/ir/core/dsl.h"
#include "watergen/ir/cpu/cpu_evaluator.h"

using namespace watergen;

namespace {

constexpr uint32_t kN = 4;

// Texel (face, i, j) holds 100 face + 10 j + i in red: every texel is distinguishable.
struct LabelledCube {
    std::vector<float> rgba = std::vector<float>(6 * kN * kN * 4, 1.0f);
    LabelledCube() {
        for (uint32_t f = 0; f < 6; ++f)
            for (uint32_t j = 0; j < kN; ++j)
                for (uint32_t i = 0; i < kN; ++i)
                    rgba[((f * kN + j) * kN + i) * 4] = static_cast<float>(label(f, i, j));
    }
    static double label(uint32_t face, uint32_t i, uint32_t j) {
        return 100.0 * face + 10.0 * j + i;
    }
    TextureView view() const { return {kN, kN, rgba.data(), 6}; }
};

// Red channel of the cube sampled along each direction (x, y, z triples).
std::vector<double> sample_red(const TextureView& cube, const std::vector<double>& dirs,
                               Filter filter = Filter::Linear) {
    Graph g;
    Expr d = varying(g, "d", Type::Vec3);
    g.set_output("out", sample(texture(g, {"cube", Type::TextureCube, "", ""}), d).x().id());
    EvalInputs in;
    in.textures["cube"] = cube;
    in.filter = filter;
    in.varyings["d"] = dirs;
    in.lanes = dirs.size() / 3;
    const EvalResult r = evaluate(g, "out", in, EvalPrecision::Double);
    if (!r.ok()) throw std::runtime_error(r.error);
    return r.values;
}

std::vector<double> direction(int face, double s, double t) {
    double d[3];
    cube_face_direction(face, s, t, d);
    return {d[0], d[1], d[2]};
}

} // namespace

TEST_CASE("cube_face_selection_follows_the_vulkan_table_for_each_major_axis", "[cube]") {
    struct Case {
        double x, y, z;
        int face;
        double s, t;
    };
    // Vulkan "Cube Map Face Selection": s = (sc / |rc| + 1) / 2, t = (tc / |rc| + 1) / 2 with
    // +X (-z, -y), -X (+z, -y), +Y (+x, +z), -Y (+x, -z), +Z (+x, -y), -Z (-x, -y).
    const Case cases[] = {
        {2, 0.5, -1, 0, 0.75, 0.375},  {-2, 0.5, -1, 1, 0.25, 0.375}, {0.5, 2, -1, 2, 0.625, 0.25},
        {0.5, -2, -1, 3, 0.625, 0.75}, {0.5, -1, 2, 4, 0.625, 0.75},  {0.5, -1, -2, 5, 0.375, 0.75},
    };
    for (const Case& c : cases) {
        INFO(c.x << " " << c.y << " " << c.z);
        const CubeFaceCoord f = cube_face_coord(c.x, c.y, c.z);
        CHECK(f.face == c.face);
        CHECK(f.s == Approx(c.s).margin(1e-15));
        CHECK(f.t == Approx(c.t).margin(1e-15));
        // The inverse lands on the same point.
        const auto d = direction(c.face, c.s, c.t);
        const double scale = std::max({std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)});
        CHECK(d[0] * scale == Approx(c.x));
        CHECK(d[1] * scale == Approx(c.y));
        CHECK(d[2] * scale == Approx(c.z));
    }
}

TEST_CASE("cube_face_ties_prefer_z_then_y_and_a_zero_direction_samples_the_z_centre", "[cube]") {
    CHECK(cube_face_coord(1, 1, 0).face == 2);   // |x| = |y|: y
    CHECK(cube_face_coord(-1, 0, 1).face == 4);  // |x| = |z|: z
    CHECK(cube_face_coord(0, -1, -1).face == 5); // |y| = |z|: z
    CHECK(cube_face_coord(1, 1, 1).face == 4);
    const CubeFaceCoord zero = cube_face_coord(0, 0, 0);
    CHECK(zero.face == 4);
    CHECK(zero.s == 0.5);
    CHECK(zero.t == 0.5);
    const CubeFaceCoord nan = cube_face_coord(NAN, 0, 1);
    CHECK(nan.face == 4);
    CHECK(nan.s == 0.5);
}

TEST_CASE("cube_texel_centres_return_their_texels_on_every_face", "[cube]") {
    const LabelledCube cube;
    std::vector<double> dirs, expected;
    for (int f = 0; f < 6; ++f)
        for (uint32_t j = 0; j < kN; ++j)
            for (uint32_t i = 0; i < kN; ++i) {
                const auto d = direction(f, (i + 0.5) / kN, (j + 0.5) / kN);
                dirs.insert(dirs.end(), d.begin(), d.end());
                expected.push_back(LabelledCube::label(static_cast<uint32_t>(f), i, j));
            }
    for (Filter filter : {Filter::Linear, Filter::Nearest}) {
        const auto r = sample_red(cube.view(), dirs, filter);
        for (size_t k = 0; k < r.size(); ++k)
            CHECK(r[k] == Approx(expected[k]).margin(1e-9));
    }
}

TEST_CASE("linear_cube_filtering_blends_across_an_edge_with_the_adjacent_face", "[cube]") {
    const LabelledCube cube;
    // On the +X / +Z edge at the height of row 1, where +Z's last column (sc = x = 1) meets
    // +X's first (sc = -z = -1). The tie picks +Z at s = 1: half of +Z (3, 1), half of the
    // texel across the edge, +X (0, 1).
    const double t = 1.5 / kN;
    const auto on_edge = direction(4, 1.0, t);
    CHECK(on_edge[0] == Approx(1.0));
    const auto r = sample_red(cube.view(), on_edge);
    CHECK(r[0] ==
          Approx(0.5 * (LabelledCube::label(4, 3, 1) + LabelledCube::label(0, 0, 1))).margin(1e-9));
    // Quarter of a texel inside +X from that edge: 3/4 of +X (0, 1), 1/4 of +Z (3, 1).
    const auto inside_x = direction(0, 0.25 / kN, t);
    const auto q = sample_red(cube.view(), inside_x);
    CHECK(q[0] == Approx(0.75 * LabelledCube::label(0, 0, 1) + 0.25 * LabelledCube::label(4, 3, 1))
                      .margin(1e-9));
    // Per-face clamp to edge would have returned texels of one face only.
    CHECK(q[0] != Approx(LabelledCube::label(0, 0, 1)).margin(1.0));
}

TEST_CASE("linear_cube_filtering_averages_the_three_texels_at_a_corner", "[cube]") {
    const LabelledCube cube;
    // (1, 1, 1): +Z at (s, t) = (1, 0). Its footprint: +Z (3, 0); across the top edge +Y (3, 3);
    // across the side edge +X (0, 0); the fourth texel lies past both edges and is the mean of
    // those three, so the result is their mean.
    const auto r = sample_red(cube.view(), {1.0, 1.0, 1.0});
    const double mean = (LabelledCube::label(4, 3, 0) + LabelledCube::label(2, 3, 3) +
                         LabelledCube::label(0, 0, 0)) /
                        3.0;
    CHECK(r[0] == Approx(mean).margin(1e-9));
    // And the same seen from the other two faces: the corner is one point.
    const auto rx = sample_red(cube.view(), {1.0, 1.0 - 1e-12, 1.0 - 1e-12});
    CHECK(rx[0] == Approx(mean).margin(1e-6));
}

TEST_CASE("linear_cube_sampling_of_smooth_content_is_continuous_across_every_edge", "[cube]") {
    // A smooth function of direction sampled at texel centres: seamless filtering is
    // continuous where the face changes; per-face clamping jumps by a texel's difference.
    constexpr uint32_t n = 8;
    std::vector<float> rgba(6 * n * n * 4, 1.0f);
    for (int f = 0; f < 6; ++f)
        for (uint32_t j = 0; j < n; ++j)
            for (uint32_t i = 0; i < n; ++i) {
                double d[3];
                cube_face_direction(f, (i + 0.5) / n, (j + 0.5) / n, d);
                const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                rgba[((f * n + j) * n + i) * 4] = static_cast<float>(
                    0.5 + 0.3 * d[0] / len + 0.2 * d[1] / len - 0.4 * d[2] / len);
            }
    const TextureView view{n, n, rgba.data(), 6};
    const double eps = 1e-9;
    int edges = 0;
    for (int f = 0; f < 6; ++f)
        for (double t : {0.3, 0.55}) {
            // Just inside and just outside the s = 0 and s = 1 edges of face f, and the t edges.
            for (auto [s0, s1, tt] : {std::tuple{eps, -eps, t}, std::tuple{1 - eps, 1 + eps, t}}) {
                std::vector<double> dirs = direction(f, s0, tt);
                const auto out = direction(f, s1, tt);
                dirs.insert(dirs.end(), out.begin(), out.end());
                const auto r = sample_red(view, dirs);
                CHECK(r[0] == Approx(r[1]).margin(1e-6));
                ++edges;
            }
            for (auto [t0, t1, ss] : {std::tuple{eps, -eps, t}, std::tuple{1 - eps, 1 + eps, t}}) {
                std::vector<double> dirs = direction(f, ss, t0);
                const auto out = direction(f, ss, t1);
                dirs.insert(dirs.end(), out.begin(), out.end());
                const auto r = sample_red(view, dirs);
                CHECK(r[0] == Approx(r[1]).margin(1e-6));
                ++edges;
            }
        }
    CHECK(edges == 48);
}

TEST_CASE("nearest_cube_sampling_clamps_within_the_face", "[cube]") {
    const LabelledCube cube;
    // s = 0.999 on +X is column 3; t = 0 is row 0; no texel of a neighbour is used.
    const auto d = direction(0, 0.999, 0.001);
    const auto r = sample_red(cube.view(), d, Filter::Nearest);
    CHECK(r[0] == LabelledCube::label(0, 3, 0));
}

TEST_CASE("a_texture_with_the_wrong_layer_count_is_an_error", "[cube]") {
    const LabelledCube cube;
    TextureView as_2d = cube.view();
    as_2d.layers = 1;
    Graph g;
    Expr d = varying(g, "d", Type::Vec3);
    g.set_output("out", sample(texture(g, {"cube", Type::TextureCube, "", ""}), d).id());
    EvalInputs in;
    in.textures["cube"] = as_2d;
    in.varyings["d"] = {1, 0, 0};
    in.lanes = 1;
    CHECK(evaluate(g, "out", in, EvalPrecision::Float).error ==
          "texture 'cube' has 1 layers; the cube binding needs 6");
    // layers = 0 (unspecified, as SyntheticScene::eval_inputs leaves it) takes the binding's.
    in.textures["cube"].layers = 0;
    CHECK(evaluate(g, "out", in, EvalPrecision::Float).ok());
}
