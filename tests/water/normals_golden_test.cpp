// Normal nodes on the CPU evaluator: 000's central differences, the derivative tangent frame
// (Schuler) and its guards, the detail map's texel-zero guard, and the analytic normal.
#include <catch2/catch.hpp>

#include <cmath>

#include "watergen/water/nodes/normals.h"
#include "watergen/water/nodes/waves.h"
#include "waves_support.h"

using namespace watergen;
using test::eval_node;

TEST_CASE("heightmap_diff_is_000s_central_difference_of_the_height_node", "[golden][normals]") {
    std::vector<double> in = {0.0, 0.0, 0.0, 3.3, -7.1, 0.0, 41.0, 12.5, 30.0};
    const auto n = eval_node("normals.heightmap_diff", in, EvalPrecision::Double);
    const double d = 0.25; // heightmap_normal_offset
    for (size_t k = 0; k < 3; ++k) {
        const double x = in[3 * k], z = in[3 * k + 1], t = in[3 * k + 2];
        const auto h =
            eval_node("waves.heightmap.height",
                      {x - d, z, t, x + d, z, t, x, z - d, t, x, z + d, t}, EvalPrecision::Double);
        // N = {W - E, 2d, S - N}, strength 1.
        const double v[3] = {h.values[0] - h.values[1], 2 * d, h.values[2] - h.values[3]};
        const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        for (int c = 0; c < 3; ++c)
            CHECK(n.values[3 * k + c] == Approx(v[c] / len).epsilon(1e-12).margin(1e-15));
        CHECK(n.values[3 * k + 1] < 1.0); // the map is not flat there
    }
}

TEST_CASE("heightmap_diff_with_zero_offset_keeps_the_plane_normal", "[golden][normals][stress]") {
    // Guard: d = 0 makes N = (0, 0, 0); normalize would return NaN.
    const std::vector<double> in = {0.0, 0.0, 0.0, 3.3, -7.1, 86400.0, 1e5, -1e5, 0.0};
    for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
        const auto n =
            eval_node("normals.heightmap_diff", in, p, {{"heightmap_normal_offset", {0.0}}});
        for (size_t k = 0; k < 3; ++k) {
            CHECK(n.values[3 * k] == 0.0);
            CHECK(n.values[3 * k + 1] == 1.0);
            CHECK(n.values[3 * k + 2] == 0.0);
        }
    }
}

TEST_CASE("analytic_normal_of_a_slope", "[golden][normals]") {
    const auto n =
        eval_node("normals.analytic", {0.3, -0.4, 0.0, 0.0, 1e30, 0.0}, EvalPrecision::Double);
    const double len = std::sqrt(0.09 + 1 + 0.16);
    CHECK(n.values[0] == Approx(-0.3 / len).epsilon(1e-15));
    CHECK(n.values[1] == Approx(1 / len).epsilon(1e-15));
    CHECK(n.values[2] == Approx(0.4 / len).epsilon(1e-15));
    CHECK(n.values[3] == 0.0);
    CHECK(n.values[4] == 1.0);
    CHECK(n.values[6] == -1.0); // a vertical wall: still finite and unit
}

namespace {

// Lanes of 2x2 quads on the plane y = a x + b z, one quad per centre, pixel steps (dx, dz) per
// screen x and (ex, ez) per screen y: the derivatives the frame sees.
std::vector<double> plane_quads(double a, double b,
                                const std::vector<std::array<double, 2>>& centres) {
    std::vector<double> lanes;
    for (const auto& c : centres)
        for (int q = 0; q < 4; ++q) {
            const double sx = q & 1, sy = q >> 1;
            const double x = c[0] + 0.05 * sx + 0.01 * sy, z = c[1] - 0.02 * sx + 0.07 * sy;
            lanes.insert(lanes.end(), {x, a * x + b * z, z});
        }
    return lanes;
}

// normals.detail_map over quads: (base, position, time) tuples.
std::vector<double> detail_tuples(const std::vector<double>& positions, const double base[3]) {
    std::vector<double> in;
    for (size_t k = 0; k < positions.size() / 3; ++k)
        in.insert(in.end(), {base[0], base[1], base[2], positions[3 * k], positions[3 * k + 1],
                             positions[3 * k + 2], 0.0});
    return in;
}

} // namespace

TEST_CASE("derivative_tangent_frame_points_along_the_world_gradients_of_u_and_v",
          "[golden][normals]") {
    // On the plane y = 0.5 x + 0.2 z with uv = 0.25 xz, the frame's tangent is the in-plane
    // gradient of u and the binormal that of v (Schuler's cotangent frame).
    const double a = 0.5, b = 0.2;
    Graph g;
    Expr p = varying(g, "p", Type::Vec3);
    const TangentFrame f = derivative_tangent_frame(g, p, p.xz() * 0.25);
    g.set_output("t", f.tangent.id());
    g.set_output("b", f.binormal.id());
    EvalInputs in;
    in.varyings["p"] = plane_quads(a, b, {{0.0, 0.0}, {10.0, -3.0}});
    in.lanes = 8;
    const auto t = evaluate(g, "t", in, EvalPrecision::Double),
               bn = evaluate(g, "b", in, EvalPrecision::Double);
    REQUIRE(t.ok());
    REQUIRE(bn.ok());
    // Surface tangents Px = (1, a, 0), Pz = (0, b, 1); grad u = G^-1 (1, 0) in that basis.
    const double gxx = 1 + a * a, gxz = a * b, gzz = 1 + b * b, det = gxx * gzz - gxz * gxz;
    auto gradient = [&](double cu, double cv,
                        double out[3]) { // coefficients (cu, cv) of (du/dx, du/dz)
        const double px = (gzz * cu - gxz * cv) / det, pz = (-gxz * cu + gxx * cv) / det;
        out[0] = px;
        out[1] = px * a + pz * b;
        out[2] = pz;
    };
    double gu[3], gv[3];
    gradient(1, 0, gu);
    gradient(0, 1, gv);
    for (size_t l = 0; l < 8; ++l) {
        CHECK(test::angle_between(&t.values[3 * l], gu) < 1e-9);
        CHECK(test::angle_between(&bn.values[3 * l], gv) < 1e-9);
    }
}

TEST_CASE("derivative_tangent_frame_is_flagged_invalid_and_stays_finite_without_uv_derivatives",
          "[golden][normals][stress]") {
    // Guard: with ddx(uv) = ddy(uv) = 0 (uv scale 0) or ddx(p) = ddy(p) = 0 (one position in the
    // whole quad) Schuler's tangent and binormal are zero vectors; normalising them would be
    // NaN. The frame reports itself invalid (detail_normal then keeps the geometric normal) and
    // its vectors stay finite. (detail_normal's own safe_normalize would hide a NaN frame, so the
    // frame is tested on its own.)
    for (double scale : {0.0, 0.25}) {
        Graph g;
        Expr p = varying(g, "p", Type::Vec3);
        const TangentFrame f = derivative_tangent_frame(g, p, p.xz() * scale);
        g.set_output(
            "out",
            vec4(f.tangent + f.binormal, select(f.valid, constant(g, 1.0), constant(g, 0.0))).id());
        EvalInputs in;
        in.varyings["p"] =
            scale == 0.0 ? plane_quads(0.1, 0.2, {{0.3, 0.7}}) : std::vector<double>(12, 1.5);
        in.lanes = 4;
        for (auto precision : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
            const auto r = evaluate(g, "out", in, precision);
            REQUIRE(r.ok());
            for (size_t l = 0; l < 4; ++l) {
                for (int c = 0; c < 3; ++c)
                    CHECK(std::isfinite(r.values[4 * l + c]));
                CHECK(r.values[4 * l + 3] == 0.0);
            }
        }
    }
}

TEST_CASE("detail_map_perturbs_the_base_normal_near_the_camera", "[golden][normals]") {
    const double up[3] = {0, 1, 0};
    const auto in = detail_tuples(plane_quads(0, 0, {{0.3, 0.7}, {2.0, 5.0}, {-4.0, 1.0}}), up);
    const auto n = eval_node("normals.detail_map", in, EvalPrecision::Double);
    for (size_t l = 0; l < n.values.size() / 3; ++l) {
        const double* v = &n.values[3 * l];
        CHECK(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) == Approx(1.0).epsilon(1e-12));
        CHECK(v[1] < 0.9999);
        CHECK(v[1] > 0.5);
    }
}

TEST_CASE("detail_map_falls_back_to_the_base_where_the_uv_derivatives_vanish",
          "[golden][normals][stress]") {
    // Guard: Schuler's frame needs uv derivatives. detail_scale 0 makes them vanish, and so do
    // a quad whose four lanes share one position; normalize(0) would be NaN.
    const double base[3] = {0.28, 0.96, 0.0};
    const auto in = detail_tuples(plane_quads(0, 0, {{0.3, 0.7}, {2.0, 5.0}}), base);
    auto still = detail_tuples({1, 0, 2, 1, 0, 2, 1, 0, 2, 1, 0, 2}, base);
    for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
        for (const auto& [tuples, uniforms] :
             {std::pair{in, test::Uniforms{{"detail_scale", {0.0, 0.0}}}},
              std::pair{still, test::Uniforms{}}}) {
            const auto n = eval_node("normals.detail_map", tuples, p, uniforms);
            for (size_t l = 0; l < n.values.size() / 3; ++l)
                for (int c = 0; c < 3; ++c)
                    CHECK(n.values[3 * l + c] == Approx(base[c]).margin(1e-3));
        }
    }
}

TEST_CASE("detail_map_texels_decoding_to_zero_keep_the_base_normal", "[golden][normals][stress]") {
    // Guard: a 0.5 grey texel decodes to (0, 0, 0) in both layers; the perturbed vector is zero
    // and normalize would be NaN. Near the camera the layers are not faded at all.
    TextureData grey{4, 4, 1, std::vector<float>(4 * 4 * 4, 0.5f)};
    const std::map<std::string, TextureData> textures = {{"detail_normal_map", grey},
                                                         {"height_map", make_height_map()}};
    const double base[3] = {0.0, 0.8, 0.6};
    const auto in = detail_tuples(plane_quads(0, 0, {{0.3, 0.7}, {2.0, 5.0}}), base);
    for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
        const auto n =
            eval_node("normals.detail_map", in, p, {{"detail_texels", {4.0}}}, &textures);
        for (size_t l = 0; l < n.values.size() / 3; ++l)
            for (int c = 0; c < 3; ++c)
                CHECK(n.values[3 * l + c] == Approx(base[c]).margin(1e-6));
    }
}

TEST_CASE("detail_map_fades_out_where_a_pixel_spans_a_large_part_of_a_tile", "[golden][normals]") {
    // 100x the pixel steps: each layer's footprint is far past detail_max_footprint.
    const double up[3] = {0, 1, 0};
    std::vector<double> far = plane_quads(0, 0, {{0.3, 0.7}});
    for (size_t k = 0; k < far.size(); ++k)
        far[k] *= 100.0;
    const auto n = eval_node("normals.detail_map", detail_tuples(far, up), EvalPrecision::Double);
    for (size_t l = 0; l < 4; ++l)
        CHECK(n.values[3 * l + 1] == Approx(1.0).margin(1e-12));
}

TEST_CASE("wave_textures_tile_seamlessly", "[golden][normals]") {
    // Texel k sits at tile coordinate k / (n - 1): the last row and column repeat the first.
    for (const TextureData& t : {make_height_map(), make_detail_normal_map()}) {
        const uint32_t n = t.width;
        for (uint32_t k = 0; k < n; ++k)
            for (int c = 0; c < 4; ++c) {
                CHECK(t.rgba[(size_t(k) * n + 0) * 4 + c] ==
                      Approx(t.rgba[(size_t(k) * n + n - 1) * 4 + c]).margin(1e-6));
                CHECK(t.rgba[(size_t(0) * n + k) * 4 + c] ==
                      Approx(t.rgba[(size_t(n - 1) * n + k) * 4 + c]).margin(1e-6));
            }
    }
    // Heights in [-1, 1]; normals unit after decoding, pointing out of the surface.
    const TextureData h = make_height_map(), d = make_detail_normal_map();
    for (size_t i = 0; i < size_t(h.width) * h.height; ++i) {
        CHECK(std::fabs(h.rgba[i * 4]) <= 1.0f);
        const double v[3] = {2.0 * d.rgba[i * 4] - 1, 2.0 * d.rgba[i * 4 + 1] - 1,
                             2.0 * d.rgba[i * 4 + 2] - 1};
        CHECK(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) == Approx(1.0).margin(1e-6));
        CHECK(v[2] > 0.5);
    }
}
