// The synthetic scene moved by a world offset (SceneView::world_offset): its textures and
// uniforms follow it, and flat water drawn over it on the CPU in double is the water at the
// origin, pixel for pixel, up to the float rounding of the position texture. CPU only.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/water/nodes/caustics.h"
#include "watergen/water/nodes/reflection.h"
#include "watergen/water/water_shader.h"

using namespace watergen;

namespace {

constexpr uint32_t kSize = 64;

SceneView moved(const std::string& view, const std::array<double, 3>& offset) {
    SceneView v = *find_scene_view(view);
    v.world_offset = offset;
    return v;
}

// Flat water (waves=flat, normals=flat) with `choices` (axis, choice) over the defaults.
Variant flat_variant(std::initializer_list<std::pair<const char*, const char*>> choices) {
    Variant v = default_variant();
    for (const char* axis : {"waves", "normals"})
        REQUIRE_FALSE(set_choice(v, axis, "flat"));
    for (const auto& [axis, choice] : choices)
        REQUIRE_FALSE(set_choice(v, axis, choice));
    return v;
}

std::vector<double> cpu_double(const Graph& fragment, const SyntheticScene& scene) {
    const EvalResult r = evaluate_image(fragment, "color", scene.eval_inputs(), scene.width,
                                        scene.height, EvalPrecision::Double);
    INFO(r.error);
    REQUIRE(r.ok());
    REQUIRE(r.components == 4);
    return r.values;
}

// Water pixels: the pass returns the scene colour itself where there is no water
// (select(is_water, colour, scene_rgb), water_shader.cpp), so a water pixel is one whose output
// differs from its scene_color texel.
std::vector<bool> water_pixels(const std::vector<double>& image, const SyntheticScene& scene) {
    const std::vector<float>& color = scene.textures.at("scene_color").rgba;
    std::vector<bool> water(image.size() / 4, false);
    for (size_t p = 0; p < water.size(); ++p)
        for (int k = 0; k < 3; ++k)
            water[p] = water[p] || image[p * 4 + k] != double(color[p * 4 + k]);
    return water;
}

size_t count(const std::vector<bool>& v) {
    size_t n = 0;
    for (bool b : v)
        n += b;
    return n;
}

} // namespace

TEST_CASE("the_scene_moves_whole_with_its_world_offset", "[views][offset]") {
    const std::array<double, 3> offset{1000.0, 3.0, -250.0};
    for (const char* name : {"sun_glint", "reflection"}) {
        INFO(name);
        const SyntheticScene at_origin = make_synthetic_scene(kSize, kSize, *find_scene_view(name));
        const SyntheticScene far = make_synthetic_scene(kSize, kSize, moved(name, offset));
        // The offset's default is 0: the scene of old, byte for byte (scene_views_test pins it).
        CHECK(preset_scene(kSize, kSize, nullptr, name).textures.at("scene_position").rgba ==
              at_origin.textures.at("scene_position").rgba);
        CHECK(at_origin.uniforms.count(caustics_window().name) == 0);
        // What does not depend on where the scene stands is the same bytes: the colour seen, the
        // planar reflection (traced around the origin), the sky, and the positions, which are
        // relative to the eye (the distance along the ray in alpha).
        for (const char* texture : {"scene_color", "reflection_map", "sky_cube", "scene_position"})
            CHECK(far.textures.at(texture).rgba == at_origin.textures.at(texture).rgba);
        CHECK(far.position_eye[0] == at_origin.position_eye[0] + offset[0]);
        const SceneView& view = *find_scene_view(name);
        CHECK(far.uniforms.at("eye_position") == std::vector<double>{view.eye[0] + offset[0],
                                                                     view.eye[1] + offset[1],
                                                                     view.eye[2] + offset[2]});
        CHECK(far.uniforms.at("water_level") == std::vector<double>{offset[1]});
        const SceneCamera cam = scene_camera(far.view, kSize, kSize);
        CHECK(cam.eye[0] == view.eye[0] + offset[0]);
        // The windows of the textures made over the scene move with it.
        const std::vector<double> window = caustics_window().default_value,
                                  origin = fourier_map_origin().default_value;
        CHECK(far.uniforms.at(caustics_window().name) ==
              std::vector<double>{window[0] + offset[0], window[1] + offset[2], window[2]});
        CHECK(far.uniforms.at(fourier_map_origin().name) ==
              std::vector<double>{origin[0] + offset[0], origin[1] + offset[2]});
        // The horizon function follows: its coefficients agree up to the rounding of the moved
        // window's texel centres (1e-13 m), far under float's spacing.
        for (const char* texture : {"fourier_coefs1", "fourier_coefs2"}) {
            const std::vector<float>&a = at_origin.textures.at(texture).rgba,
                  &b = far.textures.at(texture).rgba;
            for (size_t i = 0; i < a.size(); ++i)
                REQUIRE(std::abs(a[i] - b[i]) <= 1e-6f * (1.0f + std::abs(a[i])));
        }
        // The planar reflection's matrix puts a water point where the camera at the origin puts
        // the same point there.
        const std::vector<double>&c3 = far.uniforms.at("reflection_view_proj_c3"),
              &c3_0 = at_origin.uniforms.at("reflection_view_proj_c3");
        double q[4], q0[4];
        const double local[3] = {0.7, 0.0, 9.0};
        for (int k = 0; k < 4; ++k) {
            q[k] = c3[size_t(k)];
            q0[k] = c3_0[size_t(k)];
            for (int c = 0; c < 3; ++c) {
                const std::string column = "reflection_view_proj_c" + std::to_string(c);
                q[k] += far.uniforms.at(column)[size_t(k)] * (local[c] + offset[size_t(c)]);
                q0[k] += at_origin.uniforms.at(column)[size_t(k)] * local[c];
            }
        }
        CHECK(q[0] / q[3] == Approx(q0[0] / q0[3]).margin(1e-9));
        CHECK(q[1] / q[3] == Approx(q0[1] / q0[3]).margin(1e-9));
    }
}

TEST_CASE("flat_water_at_a_world_offset_is_the_water_at_the_origin", "[views][offset]") {
    // Flat water does not depend on where it stands: every difference between the offsets comes
    // from scene_position, which holds the moved world positions rounded to float. At x in
    // [512, 1024) m float's spacing is 2^-14 = 6.1e-5 m, so a scene point moves by at most
    // 3.05e-5 m along x against its place at the origin (there |x| < 64 m: 3.8e-6 m). The
    // colour of a water pixel depends on its scene point through the view ray and the water
    // path (extinction, the refracted ray's and the reflection's projections): at most ~1 per
    // metre of the point under these views (the nearest water lies 2 m from the eye and the
    // extinction coefficients are below 1/m), so a pixel may move by 3.05e-5 x 1 plus the
    // double evaluation's own noise: 1e-4 bounds it with room to spare (measured: 1.1e-5, the
    // sun's highlight in sun_glint, whose view rays turn by up to 3.05e-5 m / 2 m). Which pixels
    // are water (the point under the plane y = water_level, where the offset is 0) does not change
    // at all.
    constexpr double kTolerance = 1e-4;
    const std::array<double, 3> km{1000.0, 0.0, 0.0};
    const std::vector<Variant> variants = {
        flat_variant({}),
        flat_variant({{"reflection", "planar_projective"},
                      {"refraction", "refracted_ray"},
                      {"scene_input", "depth_buffer"}}),
        flat_variant({{"reflection", "fourier_horizon"}, {"refraction", "screen_distort"}}),
    };
    for (const Variant& v : variants) {
        const WaterShader shader = build_water_shader(v);
        REQUIRE_FALSE(has_errors(shader.fragment.diagnostics()));
        for (const char* name : {"sun_glint", "grazing"}) {
            INFO(v.key() << ", view " << name);
            const SyntheticScene s0 = make_synthetic_scene(kSize, kSize, *find_scene_view(name));
            const SyntheticScene s1 = make_synthetic_scene(kSize, kSize, moved(name, km));
            const std::vector<double> a = cpu_double(shader.fragment, s0),
                                      b = cpu_double(shader.fragment, s1);
            double worst = 0;
            for (size_t i = 0; i < a.size(); ++i)
                worst = std::max(worst, std::abs(a[i] - b[i]));
            const std::vector<bool> water = water_pixels(a, s0);
            std::printf("%s, view %s, offset 1 km: max |offset - origin| %.3g over %zu water "
                        "pixels\n",
                        v.key().c_str(), name, worst, count(water));
            CHECK(worst <= kTolerance);
            CHECK(count(water) >= kSize * kSize / 4);
            CHECK(water_pixels(b, s1) == water);
        }
    }
}

TEST_CASE("the_water_stays_in_view_far_from_the_origin", "[views][offset]") {
    // Before the offset moved the whole scene, only the eye moved (--set eye_position) and the
    // water vanished past 10 km: at 100 km and 1000 km it must still cover exactly the pixels
    // it covers at the origin.
    const std::vector<Variant> variants = {
        flat_variant({}),
        flat_variant({{"reflection", "planar_projective"},
                      {"refraction", "refracted_ray"},
                      {"scene_input", "depth_buffer"}}),
    };
    for (const Variant& v : variants) {
        const WaterShader shader = build_water_shader(v);
        REQUIRE_FALSE(has_errors(shader.fragment.diagnostics()));
        for (const char* name : {"sun_glint", "grazing"}) {
            const SyntheticScene s0 = make_synthetic_scene(kSize, kSize, *find_scene_view(name));
            const std::vector<bool> water = water_pixels(cpu_double(shader.fragment, s0), s0);
            REQUIRE(count(water) >= kSize * kSize / 4);
            for (double x : {1e5, 1e6}) {
                INFO(v.key() << ", view " << name << ", offset " << x << " m");
                const SyntheticScene s = make_synthetic_scene(kSize, kSize, moved(name, {x, 0, 0}));
                CHECK(water_pixels(cpu_double(shader.fragment, s), s) == water);
            }
        }
    }
}

TEST_CASE("preset_scene_moves_the_scene_and_the_presets_positions", "[views][offset]") {
    const std::array<double, 3> offset{-2e5, 0.0, 4e5};
    const SyntheticScene s = preset_scene(16, 16, nullptr, "open_water", offset);
    CHECK(s.view.name == "open_water");
    CHECK(s.view.world_offset == offset);
    CHECK(s.uniforms.at("eye_position")[0] == -2e5);
    CHECK(s.uniforms.at("eye_position")[2] == 4e5 + 30.0);
    // A position given in the scene's own frame is moved; any other value is left as it is.
    CHECK(placed_scene_value("eye_position", {1, 2, 3}, offset) ==
          std::vector<double>{1 - 2e5, 2, 3 + 4e5});
    CHECK(placed_scene_value("water_level", {0.5}, {0, 7, 0}) == std::vector<double>{7.5});
    CHECK(placed_scene_value("caustics_window", {-5, -5, 10}, offset) ==
          std::vector<double>{-5 - 2e5, -5 + 4e5, 10});
    CHECK(placed_scene_value("time", {3}, offset) == std::vector<double>{3});
}
