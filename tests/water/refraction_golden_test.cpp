// Refraction nodes on the CPU: golden values (screen displacement, 002's W = U + dv R with
// Snell's law, its projection with the scene camera) and one test per guard (shore fade,
// zero fade depth, clamped dv incl. +inf depth, total internal reflection, q.w <= 0).
#include <catch2/catch.hpp>

#include <cmath>

#include "reflection_support.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/runtime/host_values.h"

using namespace watergen;
using test::eval_catalog;

namespace {

const double kDeg = M_PI / 180.0;

// uv of a world point seen by the scene camera (v down), by hand.
std::pair<double, double> screen_uv(const SceneCamera& c, const double p[3]) {
    double x = 0, y = 0, w = 0;
    for (int k = 0; k < 3; ++k) {
        const double d = p[k] - c.eye[k];
        x += d * c.right[k];
        y += d * c.up[k];
        w += d * c.forward[k];
    }
    return {0.5 + 0.5 * x / (w * c.tan_half_fov_y * c.aspect),
            0.5 - 0.5 * y / (w * c.tan_half_fov_y)};
}

test::Uniforms clip_matrix(double qx, double w) {
    return {{"refraction_view_proj_c0", {0, 0, 0, 0}},
            {"refraction_view_proj_c1", {0, 0, 0, 0}},
            {"refraction_view_proj_c2", {0, 0, 0, 0}},
            {"refraction_view_proj_c3", {qx, 0.2, 0, w}}};
}

} // namespace

TEST_CASE("screen_distort_displaces_uv_by_the_horizontal_normal", "[refraction][golden]") {
    // uv + N.xz * 0.03 * saturate(depth / 1 m).
    const auto r =
        eval_catalog("refraction.screen_distort_uv", {0.5, 0.5, 0.1, 1, -0.2, 5.0, 0.5, 0.5, 0.1, 1,
                                                      -0.2, 0.5, 0.5, 0.5, 0.1, 1, -0.2, INFINITY});
    CHECK(r.at(0, 0) == Approx(0.503).margin(1e-12));
    CHECK(r.at(0, 1) == Approx(0.494).margin(1e-12));
    CHECK(r.at(1, 0) == Approx(0.5015).margin(1e-12));
    CHECK(r.at(1, 1) == Approx(0.497).margin(1e-12));
    CHECK(r.at(2, 0) == Approx(0.503).margin(1e-12));
}

TEST_CASE("screen_distort_does_not_displace_at_the_shoreline", "[refraction][guard]") {
    // Guard (003's "artifacts along water edges"): at depth 0 (and a scene a hair above the
    // plane) the displacement fades out, so dry land is not smeared into the water.
    const auto r = eval_catalog("refraction.screen_distort_uv",
                                {0.5, 0.5, 0.1, 1, -0.2, 0.0, 0.5, 0.5, 0.1, 1, -0.2, -1e-3});
    for (size_t i = 0; i < 2; ++i) {
        CHECK(r.at(i, 0) == 0.5);
        CHECK(r.at(i, 1) == 0.5);
    }
}

TEST_CASE("screen_distort_with_a_zero_fade_depth_displaces_everywhere", "[refraction][guard]") {
    // Guard: a fade depth of 0 turns the fade off; depth / 0 would be 0 / 0 at the shoreline
    // (NaN, and clamp(NaN) is undefined on GPUs; the CPU's gives 0, no displacement).
    for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
        const auto r = eval_catalog("refraction.screen_distort_uv",
                                    {0.5, 0.5, 0.1, 1, -0.2, 1e-3, 0.5, 0.5, 0.1, 1, -0.2, 0.0}, p,
                                    {{"refraction_shore_fade_depth", {0.0}}});
        const double m = p == EvalPrecision::Half ? 1e-3 : 1e-7;
        for (size_t i = 0; i < 2; ++i) {
            CHECK(r.at(i, 0) == Approx(0.503).margin(m));
            CHECK(r.at(i, 1) == Approx(0.494).margin(m));
        }
    }
}

TEST_CASE("screen_distort_keeps_uv_on_the_screen", "[refraction][golden]") {
    const auto r = eval_catalog("refraction.screen_distort_uv", {0.999, 0.001, 1, 0, -1, 5.0},
                                EvalPrecision::Double, {{"refraction_distortion", {1.0}}});
    CHECK(r.at(0, 0) == 1.0);
    CHECK(r.at(0, 1) == 0.0);
}

TEST_CASE("refracted_ray_point_follows_snells_law_with_the_clamped_dv", "[refraction][golden]") {
    // 002: dv = clamp(depth, 0, 2) / 3; R = refract(-V, N, 1 / 1.33333).
    const double s = std::sin(40 * kDeg), c = std::cos(40 * kDeg);
    const auto r = eval_catalog("refraction.refracted_ray_point",
                                {
                                    1, 0, 5, 0, -1, 0, 0, 1, 0, 1.2,      // normal incidence
                                    1, 0, 5, 0, -1, 0, 0, 1, 0, INFINITY, // bottomless: dv = 2/3
                                    1, 0, 5, 0, -1, 0, 0, 1, 0, 1e30,     //
                                    1, 0, 5, 0, -1, 0, 0, 1, 0, -1.0,     // above the plane: W = U
                                    1, 0, 5, s, -c, 0, 0, 1, 0, 0.9,      // 40 degrees
                                });
    CHECK(r.at(0, 1) == Approx(-0.4).margin(1e-12));
    CHECK(r.at(1, 1) == Approx(-2.0 / 3.0).margin(1e-12));
    CHECK(r.at(2, 1) == Approx(-2.0 / 3.0).margin(1e-12));
    CHECK(r.at(3, 0) == 1.0);
    CHECK(r.at(3, 1) == 0.0);
    CHECK(r.at(3, 2) == 5.0);
    const double st = s / 1.33333, ct = std::sqrt(1 - st * st);
    CHECK(r.at(4, 0) == Approx(1 + 0.3 * st).margin(1e-12));
    CHECK(r.at(4, 1) == Approx(-0.3 * ct).margin(1e-12));
    CHECK(r.at(4, 2) == Approx(5.0).margin(1e-12));
}

TEST_CASE("refracted_ray_uv_projects_w_with_the_scene_camera", "[refraction][golden]") {
    const SyntheticScene scene = make_synthetic_scene(16, 16);
    const SceneCamera cam = scene_camera(16, 16);
    // The water point seen at pixel uv (0.4, 0.8), 1.5 m deep: W = U + 0.5 R.
    const double sx = (2 * 0.4 - 1) * cam.tan_half_fov_y * cam.aspect,
                 sy = (1 - 2 * 0.8) * cam.tan_half_fov_y;
    double d[3], u[3];
    double len = 0;
    for (int k = 0; k < 3; ++k) {
        d[k] = cam.forward[k] + cam.right[k] * sx + cam.up[k] * sy;
        len += d[k] * d[k];
    }
    len = std::sqrt(len);
    for (double& x : d)
        x /= len;
    const double t = -cam.eye[1] / d[1];
    for (int k = 0; k < 3; ++k)
        u[k] = cam.eye[k] + d[k] * t;
    const auto w = eval_catalog("refraction.refracted_ray_point",
                                {u[0], u[1], u[2], d[0], d[1], d[2], 0, 1, 0, 1.5});
    const double wp[3] = {w.at(0, 0), w.at(0, 1), w.at(0, 2)};
    const auto expected = screen_uv(cam, wp);
    // The node reads the point in the shader's frame (host_values.h).
    const FrameCentre centre = frame_centre_of(cam.eye[0], cam.eye[2]);
    const auto r = eval_catalog(
        "refraction.refracted_ray_uv",
        {0.4, 0.8, u[0] - centre.x, u[1], u[2] - centre.z, d[0], d[1], d[2], 0, 1, 0, 1.5},
        EvalPrecision::Double, scene.uniforms);
    CHECK(r.at(0, 0) == Approx(expected.first).margin(1e-12));
    CHECK(r.at(0, 1) == Approx(expected.second).margin(1e-12));
    // The bent ray lands further down the screen than the straight one would at that depth.
    CHECK(r.at(0, 1) > 0.8);
}

TEST_CASE("refracted_ray_falls_back_to_the_undistorted_uv_under_total_internal_reflection",
          "[refraction][guard]") {
    // Guard (002 via refract()): from the water side (n1 = 1.33333, n2 = 1) at 60 degrees
    // refract() returns 0 and no light crosses: W = U, and the uv is the pixel's own, not
    // where U happens to project.
    const SyntheticScene scene = make_synthetic_scene(16, 16);
    test::Uniforms uniforms = scene.uniforms;
    uniforms["ior_air"] = {1.33333};
    uniforms["ior_water"] = {1.0};
    const double s = std::sin(60 * kDeg), c = std::cos(60 * kDeg);
    const auto w = eval_catalog("refraction.refracted_ray_point", {3, 0, 9, s, -c, 0, 0, 1, 0, 1.5},
                                EvalPrecision::Double, uniforms);
    CHECK(w.at(0, 0) == 3.0);
    CHECK(w.at(0, 1) == 0.0);
    CHECK(w.at(0, 2) == 9.0);
    for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
        const auto r = eval_catalog("refraction.refracted_ray_uv",
                                    {0.2, 0.7, 3, 0, 9, s, -c, 0, 0, 1, 0, 1.5}, p, uniforms);
        CHECK(r.at(0, 0) == Approx(0.2).margin(1e-3));
        CHECK(r.at(0, 1) == Approx(0.7).margin(1e-3));
    }
}

TEST_CASE("refracted_ray_falls_back_to_the_undistorted_uv_on_and_behind_the_camera_plane",
          "[refraction][guard]") {
    // water-models.md stress: q.w in {-1, -1e-6, 0, 1e-6} (and 0 / 0 with q.x = 0).
    for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half})
        for (double qx : {0.3, 0.0})
            for (double w : {-1.0, -1e-6, 0.0, 1e-6, 1.0}) {
                INFO(to_string(p) << " q.x " << qx << " w " << w);
                const auto r = eval_catalog("refraction.refracted_ray_uv",
                                            {0.2, 0.7, 1, 0, 5, 0, -1, 0, 0, 1, 0, 1.0}, p,
                                            clip_matrix(qx, w));
                const double m = p == EvalPrecision::Half ? 1e-3 : 1e-7;
                CHECK(std::isfinite(r.at(0, 0)));
                CHECK(std::isfinite(r.at(0, 1)));
                CHECK(r.at(0, 0) == Approx(w == 1.0 ? 0.5 + 0.5 * qx : 0.2).margin(m));
                CHECK(r.at(0, 1) == Approx(w == 1.0 ? 0.6 : 0.7).margin(m));
            }
}

TEST_CASE("refracted_ray_uv_stays_on_the_screen", "[refraction][golden]") {
    const auto r =
        eval_catalog("refraction.refracted_ray_uv", {0.2, 0.7, 1, 0, 5, 0, -1, 0, 0, 1, 0, 1.0},
                     EvalPrecision::Double, clip_matrix(3.0, 1.0));
    CHECK(r.at(0, 0) == 1.0);
}
