// Reflection nodes on the CPU: golden values (003's trig-free Fourier series against the
// trig form, projective uv of known points) and one test per guard (lower hemisphere,
// vertical ray, q.w <= 0 incl. water-models.md's stress values, zero band / transition / FOV).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "reflection_support.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/runtime/host_values.h"
#include "watergen/water/axis_registry.h"
#include "watergen/water/nodes/reflection.h"
#include "watergen/water/surface.h"

using namespace watergen;
using test::eval_catalog;

namespace {

const double kC1[4] = {0.08, 0.03, -0.05, 0.02};    // a0, a1, b1, a2
const double kC2[4] = {0.015, -0.01, 0.007, 0.004}; // b2, a3, b3, a4

double trig_series(double t) {
    return kC1[0] + kC1[1] * std::cos(t) + kC1[2] * std::sin(t) + kC1[3] * std::cos(2 * t) +
           kC2[0] * std::sin(2 * t) + kC2[1] * std::cos(3 * t) + kC2[2] * std::sin(3 * t) +
           kC2[3] * std::cos(4 * t);
}

std::vector<double> fourier_tuple(double rx, double ry, double rz) {
    return {kC1[0], kC1[1], kC1[2], kC1[3], kC2[0], kC2[1], kC2[2], kC2[3], rx, ry, rz};
}

double smoothstep(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

// A 1x1-per-face cube: upper faces blue, -Y red, sides green; only the face matters.
struct TwoToneCube {
    std::vector<float> rgba;
    TwoToneCube() {
        const float faces[6][4] = {{0, 1, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1},
                                   {1, 0, 0, 1}, {0, 1, 0, 1}, {0, 1, 0, 1}};
        for (const auto& f : faces)
            rgba.insert(rgba.end(), f, f + 4);
    }
};

// The reflection choice composed over varyings standing for the surface fields it reads.
EvalResult reflect_with(const std::string& choice, const std::vector<double>& view_rays,
                        const std::vector<double>& normals, const std::vector<double>& points,
                        EvalInputs in) {
    Graph g;
    Surface s(g);
    s.view_ray = varying(g, "view_ray", Type::Vec3);
    s.normal = varying(g, "normal", Type::Vec3);
    s.surface_point = varying(g, "surface_point", Type::Vec3);
    compose_choice(s, "reflection", choice);
    g.set_output("out", s.reflected.id());
    in.varyings["view_ray"] = view_rays;
    in.varyings["normal"] = normals;
    in.varyings["surface_point"] = points;
    in.lanes = view_rays.size() / 3;
    return evaluate(g, "out", in, EvalPrecision::Double);
}

} // namespace

TEST_CASE("fourier_series_trig_free_equals_the_trig_form", "[reflection][golden]") {
    // 003: EvaluateFourier from the normalised (x, y) = (R.x, R.z); the horizontal part here
    // has length 2 and a vertical component, which the azimuth must ignore.
    for (double t : {0.0, 0.3, 1.0, 2.0, M_PI / 2, 3.0, -2.5, 5.0, M_PI}) {
        INFO("t = " << t);
        const auto r = eval_catalog("reflection.fourier_series",
                                    fourier_tuple(2 * std::cos(t), 0.7, 2 * std::sin(t)));
        CHECK(r.at(0) == Approx(trig_series(t)).epsilon(1e-12).margin(1e-15));
    }
}

TEST_CASE("fourier_series_of_a_vertical_ray_is_finite", "[reflection][guard]") {
    // Guard: the seed normalises (R.x, R.z) = 0 for a vertical ray, which is NaN.
    for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
        INFO(to_string(p));
        std::vector<double> tuples;
        for (double ry : {1.0, -1.0})
            for (const auto& t : {fourier_tuple(0, ry, 0), fourier_tuple(1e-30, ry, -1e-30)})
                tuples.insert(tuples.end(), t.begin(), t.end());
        const auto series = eval_catalog("reflection.fourier_series", tuples, p);
        for (double v : series.values)
            CHECK(std::isfinite(v));
        // The fallback azimuth is t = 0.
        CHECK(series.at(0) ==
              Approx(trig_series(0.0)).margin(p == EvalPrecision::Half ? 2e-3 : 1e-7));
        const auto weight = eval_catalog("reflection.fourier_sky_weight", tuples, p);
        CHECK(weight.at(0) == 1.0); // straight up: sky
        CHECK(weight.at(1) == 1.0);
        CHECK(weight.at(2) == 0.0); // straight down: below any horizon
        CHECK(weight.at(3) == 0.0);
    }
}

TEST_CASE("fourier_sky_weight_compares_the_elevation_with_the_horizon", "[reflection][golden]") {
    // Horizon at tan h = a0 = 0.08 everywhere (other coefficients 0); the weight is
    // smoothstep(-w, w, sin(elevation - h)).
    const double h = std::atan(0.08);
    for (double transition : {0.02, 1.0}) {
        for (double e : {-0.3, 0.0, h - 0.01, h, h + 0.01, 0.2, 1.2}) {
            INFO("transition " << transition << " elevation " << e);
            const std::vector<double> tuple = {
                0.08, 0, 0, 0, 0, 0, 0, 0, std::cos(e) * 0.6, std::sin(e), std::cos(e) * 0.8};
            const auto r =
                eval_catalog("reflection.fourier_sky_weight", tuple, EvalPrecision::Double,
                             {{"fourier_transition", {transition}}});
            CHECK(r.at(0) ==
                  Approx(smoothstep(-transition, transition, std::sin(e - h))).margin(1e-12));
        }
    }
}

TEST_CASE("fourier_transition_of_zero_still_gives_a_defined_step", "[reflection][guard]") {
    // Guard: smoothstep(-0, 0, x) divides 0 by 0 (undefined in GLSL); the range floor 1e-3 holds.
    const double h = std::atan(0.08);
    const std::vector<double> tuple = {
        0.08, 0, 0, 0, 0, 0, 0, 0, std::cos(h + 5e-4), std::sin(h + 5e-4), 0};
    const auto r = eval_catalog("reflection.fourier_sky_weight", tuple, EvalPrecision::Double,
                                {{"fourier_transition", {0.0}}});
    CHECK(r.at(0) == Approx(smoothstep(-1e-3, 1e-3, std::sin(5e-4))).margin(1e-9));
}

TEST_CASE("sky_lookup_reflects_the_view_ray_and_mirrors_the_lower_hemisphere",
          "[reflection][golden]") {
    const double n = std::sqrt(1 + 0.25 + 4);
    // From above onto a flat surface: R = (1, 0.5, 2) / |.|, no tint.
    auto r = eval_catalog("reflection.sky_lookup", {1 / n, -0.5 / n, 2 / n, 0, 1, 0});
    CHECK(r.at(0, 0) == Approx(1 / n));
    CHECK(r.at(0, 1) == Approx(0.5 / n));
    CHECK(r.at(0, 2) == Approx(2 / n));
    CHECK(r.at(0, 3) == 0.0);
    // A view ray from below the plane (a normal tilted past the ray) so that R points down
    // (R.y = -0.6, -0.1): the lookup stays in the upper half and the tint weight is
    // smoothstep(0, 0.2, -R.y).
    r = eval_catalog("reflection.sky_lookup",
                     {0, 0.6, 0.8, 0, 1, 0, 0, 0.1, std::sqrt(1 - 0.1 * 0.1), 0, 1, 0});
    CHECK(r.at(0, 1) == Approx(0.6));
    CHECK(r.at(0, 3) == 1.0);
    CHECK(r.at(1, 1) == Approx(0.1));
    CHECK(r.at(1, 3) == Approx(0.5));
    // A zero view ray (eye on the scene point) looks at the zenith instead of a zero vector.
    r = eval_catalog("reflection.sky_lookup", {0, 0, 0, 0, 1, 0});
    CHECK(r.at(0, 0) == 0.0);
    CHECK(r.at(0, 1) == 1.0);
    CHECK(r.at(0, 2) == 0.0);
}

TEST_CASE("sky_cubemap_never_shows_the_cube_below_the_horizon", "[reflection][guard]") {
    // Guard (001): the lower half of the cube is red here; a reflected ray pointing down must
    // get the mirrored upper half (blue) tinted by reflection_lower_tint, never red.
    const TwoToneCube cube;
    EvalInputs in;
    in.textures["sky_cube"] = TextureView{1, 1, cube.rgba.data(), 6};
    in.uniforms["reflection_lower_tint"] = {0.5, 0.5, 0.5};
    const double d = std::sqrt(0.5);
    // view rays: up at 45 degrees (R points down, 45 degrees), and down (R up): flat normal.
    const auto r = reflect_with("sky_cubemap", {0, d, d, 0, -d, d}, {0, 1, 0, 0, 1, 0},
                                {0, 0, 0, 0, 0, 0}, in);
    REQUIRE(r.ok());
    // 45 degrees sits on the +Y / +Z edge: half blue, half green (seamless), times the tint.
    CHECK(r.values[0] == 0.0);
    CHECK(r.values[1] == Approx(0.25));
    CHECK(r.values[2] == Approx(0.25));
    CHECK(r.values[3] == 0.0);
    CHECK(r.values[4] == Approx(0.5));
    CHECK(r.values[5] == Approx(0.5));
}

TEST_CASE("sky_lookup_with_a_zero_band_steps_at_the_range_floor", "[reflection][guard]") {
    // Guard: smoothstep(0, 0, x) is undefined in GLSL; the band is held at its range minimum.
    const auto r = eval_catalog("reflection.sky_lookup", {0, 5e-4, 1, 0, 1, 0},
                                EvalPrecision::Double, {{"reflection_horizon_band", {0.0}}});
    CHECK(r.at(0, 3) == Approx(0.5).margin(1e-9)); // smoothstep(0, 1e-3, 5e-4)
}

TEST_CASE("projective_uv_of_points_on_the_water_matches_the_screen", "[reflection][golden]") {
    // The scene's matrices (scene_optics_inputs.cpp). A point of the water plane seen at pixel
    // uv projects with the main camera to uv, and with the mirrored camera to the same place
    // of the reflection texture, whose field of view is 1.5x wider (002): 0.5 + (uv - 0.5) / 1.5.
    const SyntheticScene scene = make_synthetic_scene(16, 16);
    const SceneCamera cam = scene_camera(16, 16);
    const FrameCentre centre = frame_centre_of(cam.eye[0], cam.eye[2]);
    std::vector<double> tuples;
    std::vector<std::pair<double, double>> uvs;
    for (double u : {0.5, 0.1, 0.93})
        for (double v : {0.55, 0.7, 0.98}) {
            const double sx = (2 * u - 1) * cam.tan_half_fov_y * cam.aspect,
                         sy = (1 - 2 * v) * cam.tan_half_fov_y;
            double d[3];
            for (int k = 0; k < 3; ++k)
                d[k] = cam.forward[k] + cam.right[k] * sx + cam.up[k] * sy;
            const double t = -cam.eye[1] / d[1];
            REQUIRE(t > 0);
            // The node reads the point in the shader's frame (host_values.h).
            tuples.insert(tuples.end(), {cam.eye[0] + d[0] * t - centre.x, 0.0,
                                         cam.eye[2] + d[2] * t - centre.z, 0, 1, 0});
            uvs.push_back({u, v});
        }
    const auto r =
        eval_catalog("reflection.projective_uv", tuples, EvalPrecision::Double, scene.uniforms);
    for (size_t i = 0; i < uvs.size(); ++i) {
        INFO(uvs[i].first << ", " << uvs[i].second);
        CHECK(r.at(i, 0) == Approx(0.5 + (uvs[i].first - 0.5) / 1.5).margin(1e-12));
        CHECK(r.at(i, 1) == Approx(0.5 + (uvs[i].second - 0.5) / 1.5).margin(1e-12));
        CHECK(r.at(i, 2) == 1.0);
    }
}

TEST_CASE("projective_uv_displaces_the_point_by_the_horizontal_normal", "[reflection][golden]") {
    // 001: P + d (N.x, 0, N.z), d = 4: a point on the plane and the same point seen through a
    // tilted normal must land where P + 4 N.xz projects.
    const SyntheticScene scene = make_synthetic_scene(16, 16);
    const double nx = 0.1, nz = -0.05, ny = std::sqrt(1 - nx * nx - nz * nz);
    const auto r = eval_catalog("reflection.projective_uv",
                                {2.0, 0.0, 10.0, nx, ny, nz, 2.0 + 4 * nx, 0.0, 10.0 + 4 * nz, 0, 1,
                                 0, 2.0, 0.0, 10.0, 0, 1, 0},
                                EvalPrecision::Double, scene.uniforms);
    CHECK(r.at(0, 0) == Approx(r.at(1, 0)).margin(1e-12));
    CHECK(r.at(0, 1) == Approx(r.at(1, 1)).margin(1e-12));
    CHECK(std::fabs(r.at(0, 0) - r.at(2, 0)) > 1e-3); // the displacement moved it
}

TEST_CASE("projective_uv_is_the_texture_centre_on_and_behind_the_camera_plane",
          "[reflection][guard]") {
    // water-models.md stress: q.w in {-1, -1e-6, 0, 1e-6}. The matrix maps every point to
    // q = (0.3, 0.2, 0, w); with q.x = 0 the divide is 0 / 0, with w = -1 it mirrors the point
    // to uv 0.4.
    for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half})
        for (double qx : {0.3, 0.0})
            for (double w : {-1.0, -1e-6, 0.0, 1e-6, 1.0}) {
                INFO(to_string(p) << " q.x " << qx << " w " << w);
                const test::Uniforms m = {{"reflection_view_proj_c0", {0, 0, 0, 0}},
                                          {"reflection_view_proj_c1", {0, 0, 0, 0}},
                                          {"reflection_view_proj_c2", {0, 0, 0, 0}},
                                          {"reflection_view_proj_c3", {qx, 0.2, 0, w}}};
                const auto r = eval_catalog("reflection.projective_uv", {5, 0, 5, 0, 1, 0}, p, m);
                for (int c = 0; c < 3; ++c)
                    CHECK(std::isfinite(r.at(0, c)));
                CHECK(r.at(0, 0) >= 0.0);
                CHECK(r.at(0, 0) <= 1.0);
                CHECK(r.at(0, 2) == (w > 0.5 ? 1.0 : 0.0));
                if (w < 0.5) {
                    // The texture centre: not a mirrored point, not 0 / 0.
                    CHECK(r.at(0, 0) == 0.5);
                    CHECK(r.at(0, 1) == 0.5);
                }
                if (w == 1.0)
                    CHECK(r.at(0, 0) == Approx(0.5 + 0.5 * qx / 1.5)
                                            .margin(p == EvalPrecision::Half ? 1e-3 : 1e-7));
            }
}

TEST_CASE("planar_projective_falls_back_to_the_sky_colour_behind_the_camera",
          "[reflection][guard]") {
    // Guard (001): q.w <= 0 has no texel. The reflection map is green; behind the camera plane
    // (w = -1, where the divide would mirror the point back into the texture) the result is
    // sky_color, in front (w = 1) the map.
    const std::vector<float> green = {0, 1, 0, 1};
    for (double w : {-1.0, 0.0, 1.0}) {
        EvalInputs in;
        in.textures["reflection_map"] = TextureView{1, 1, green.data(), 1};
        in.uniforms = {{"reflection_view_proj_c0", {0, 0, 0, 0}},
                       {"reflection_view_proj_c1", {0, 0, 0, 0}},
                       {"reflection_view_proj_c2", {0, 0, 0, 0}},
                       {"reflection_view_proj_c3", {0.3, 0.2, 0, w}}};
        const auto r = reflect_with("planar_projective", {0, -1, 0}, {0, 1, 0}, {1, 0, 1}, in);
        REQUIRE(r.ok());
        const std::vector<double> expected =
            w > 0 ? std::vector<double>{0, 1, 0} : sky_color().default_value;
        for (int c = 0; c < 3; ++c)
            CHECK(r.values[static_cast<size_t>(c)] == Approx(expected[static_cast<size_t>(c)]));
    }
}

TEST_CASE("projective_uv_with_a_zero_fov_extension_uses_the_range_floor", "[reflection][guard]") {
    // Guard: a FOV extension of 0 would divide by 0 (uv pinned to the border); the range
    // minimum 1 (no extension) is used instead.
    const test::Uniforms m = {{"reflection_view_proj_c0", {0, 0, 0, 0}},
                              {"reflection_view_proj_c1", {0, 0, 0, 0}},
                              {"reflection_view_proj_c2", {0, 0, 0, 0}},
                              {"reflection_view_proj_c3", {0.3, 0.2, 0, 1}},
                              {"reflection_fov_extension", {0.0}}};
    const auto r =
        eval_catalog("reflection.projective_uv", {5, 0, 5, 0, 1, 0}, EvalPrecision::Double, m);
    CHECK(r.at(0, 0) == Approx(0.65));
    CHECK(r.at(0, 1) == Approx(0.6));
}

TEST_CASE("fourier_horizon_is_dark_below_and_sky_above", "[reflection][golden]") {
    // A 1x1 coefficient map with a horizon at tan h = 0.1: a view ray reflected 20 degrees up
    // sees sky_color, 1 degree up sees fourier_below_color.
    const std::vector<float> c1 = {0.1f, 0, 0, 0}, c2 = {0, 0, 0, 0};
    EvalInputs in;
    in.textures["fourier_coefs1"] = TextureView{1, 1, c1.data(), 1};
    in.textures["fourier_coefs2"] = TextureView{1, 1, c2.data(), 1};
    const double a = 20 * M_PI / 180, b = 1 * M_PI / 180;
    const auto r = reflect_with("fourier_horizon",
                                {0, -std::sin(a), std::cos(a), 0, -std::sin(b), std::cos(b)},
                                {0, 1, 0, 0, 1, 0}, {0, 0, 0, 0, 0, 0}, in);
    REQUIRE(r.ok());
    for (int c = 0; c < 3; ++c) {
        CHECK(r.values[static_cast<size_t>(c)] ==
              Approx(sky_color().default_value[static_cast<size_t>(c)]));
        CHECK(r.values[3 + static_cast<size_t>(c)] ==
              Approx(std::vector<double>{0.05, 0.07, 0.06}[static_cast<size_t>(c)]));
    }
}
