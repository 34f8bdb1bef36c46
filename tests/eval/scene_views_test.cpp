// The named views of the synthetic scene (render/scene_views.h): beach is the scene every render
// used before views existed, byte for byte; every view's matrices follow its camera; the
// reflection view's buoy shows in the planar reflection; lavapipe and the CPU agree in every view.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "doc_text.h"
#include "render_agreement.h"
#include "shared_runner.h"
#include "watergen/eval/bench/accuracy_bench.h"
#include "watergen/eval/compare/view_separation.h"
#include "watergen/pipeline/variant/variant_build.h"

using namespace watergen;

namespace {

// FNV-1a over the scene's bytes: size, then every texture (name, shape, texels) and every
// uniform (name, values) in map order.
struct Fnv1a {
    uint64_t hash = 1469598103934665603ull;
    void add(const void* data, size_t n) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; ++i)
            hash = (hash ^ bytes[i]) * 1099511628211ull;
    }
};

uint64_t scene_hash(const SyntheticScene& s) {
    Fnv1a f;
    f.add(&s.width, sizeof s.width);
    f.add(&s.height, sizeof s.height);
    for (const auto& [name, t] : s.textures) {
        // Added after the hashes below were taken, and read by caustics variants only:
        // scene_caustics_inputs_test pins their values. scene_depth (depth-buffer variants
        // only) is made from scene_position; depth_buffer_render_test checks it against it.
        if (name == "caustics_tile" || name == "caustics_map" || name == "scene_depth") continue;
        f.add(name.data(), name.size());
        for (uint32_t v : {t.width, t.height, t.layers})
            f.add(&v, sizeof v);
        f.add(t.rgba.data(), t.rgba.size() * sizeof(float));
    }
    for (const auto& [name, values] : s.uniforms) {
        if (name.rfind("scene_inv_view_proj_c", 0) == 0) continue; // with scene_depth
        f.add(name.data(), name.size());
        f.add(values.data(), values.size() * sizeof(double));
    }
    return f.hash;
}

// Where the view-projection columns `prefix`_view_proj_c0..c3 put world point p: uv in [0, 1]^2.
std::array<double, 2> project(const SyntheticScene& s, const std::string& prefix,
                              const std::array<double, 3>& p) {
    double q[4] = {};
    for (int c = 0; c < 4; ++c) {
        const std::vector<double>& col = s.uniforms.at(prefix + "_view_proj_c" + std::to_string(c));
        const double w = c < 3 ? p[c] : 1.0;
        for (int k = 0; k < 4; ++k)
            q[k] += col[k] * w;
    }
    return {0.5 * q[0] / q[3] + 0.5, 0.5 * q[1] / q[3] + 0.5};
}

} // namespace

TEST_CASE("beach_view_reproduces_the_scene_of_old_byte_for_byte", "[views]") {
    // Hashes of make_synthetic_scene: at 50bb774, before views, every golden value and render
    // figure of the other tests was measured over the scene; since scene_position holds each
    // point less the eye (camera-relative, rounded to float once) the hashes are of those bytes,
    // every other texture and uniform as it was.
    const struct {
        uint32_t width, height;
        uint64_t hash;
    } kScenes[] = {{40, 24, 0x433d338e35806701ull},
                   {64, 64, 0xdeef13aff9780febull},
                   {97, 61, 0x85ac542760b821e4ull}};
    for (const auto& k : kScenes) {
        INFO(k.width << "x" << k.height);
        const SyntheticScene old = make_synthetic_scene(k.width, k.height);
        const SyntheticScene beach = make_synthetic_scene(k.width, k.height, beach_view());
        CHECK(scene_hash(old) == k.hash);
        CHECK(scene_hash(beach) == k.hash);
        CHECK(beach.view.name == "beach");
        CHECK(old.view.name == "beach");
    }
}

TEST_CASE("views_have_one_name_each_and_the_default_comes_first", "[views]") {
    const std::vector<SceneView>& views = scene_views();
    REQUIRE(views.size() >= 6);
    CHECK(views.front().name == "beach");
    CHECK(&beach_view() == &views.front());
    std::set<std::string> names;
    for (const SceneView& v : views) {
        INFO(v.name);
        CHECK(names.insert(v.name).second);
        CHECK(find_scene_view(v.name) == &v);
        CHECK_FALSE(v.description.empty());
        CHECK(v.eye[1] > 0.0); // the water pass assumes the eye above the water
    }
    for (const char* name : {"sun_glint", "grazing", "shoreline", "open_water", "reflection"})
        CHECK(find_scene_view(name) != nullptr);
    CHECK(find_scene_view("sunset") == nullptr);
    CHECK(scene_view_names() == "beach, sun_glint, grazing, shoreline, open_water, reflection");
    // Only the reflection view stands something out of the water.
    for (const SceneView& v : views)
        CHECK(v.standing_sphere.has_value() == (v.name == "reflection"));
}

TEST_CASE("every_view_projects_with_its_own_camera", "[views]") {
    // Nodes that project world points (planar reflection, refracted_ray) read the matrices:
    // the refraction matrix must put every scene point back on the pixel that sees it, and the
    // reflection matrix its mirror image (in y = 0) on the same pixel.
    const uint32_t w = 48, h = 32;
    std::set<std::vector<float>> images;
    for (const SceneView& view : scene_views()) {
        INFO(view.name);
        const SyntheticScene s = make_synthetic_scene(w, h, view);
        CHECK(s.view.name == view.name);
        CHECK(s.uniforms.at("eye_position") ==
              std::vector<double>{view.eye[0], view.eye[1], view.eye[2]});
        const std::vector<double>& sun = s.uniforms.at("sun_direction");
        CHECK(std::hypot(sun[0], sun[1], sun[2]) == Approx(1.0).epsilon(1e-12));
        CHECK(sun[1] * view.sun_travel[1] > 0.0);
        const SceneCamera cam = scene_camera(view, w, h);
        CHECK(cam.eye[1] == view.eye[1]);
        CHECK(std::asin(cam.forward[1]) * 180.0 / 3.14159265358979 ==
              Approx(view.pitch_degrees).margin(1e-9));
        const std::vector<float>& position = s.textures.at("scene_position").rgba;
        size_t hits = 0;
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) {
                const float* p = &position[(size_t(y) * w + x) * 4];
                if (p[3] >= 1000.0f) continue; // sky
                ++hits;
                // The texel is the point less the eye.
                const std::array<double, 3> at{view.eye[0] + p[0], view.eye[1] + p[1],
                                               view.eye[2] + p[2]},
                    mirrored{at[0], -at[1], at[2]};
                const auto uv = project(s, "refraction", at),
                           mirror_uv = project(s, "reflection", mirrored);
                CHECK(uv[0] == Approx((x + 0.5) / w).margin(1e-4));
                CHECK(uv[1] == Approx((y + 0.5) / h).margin(1e-4));
                CHECK(mirror_uv[0] == Approx(uv[0]).margin(1e-4));
                CHECK(mirror_uv[1] == Approx(uv[1]).margin(1e-4));
            }
        CHECK(hits >= w * h / 8);
        CHECK(images.insert(s.textures.at("scene_color").rgba).second); // a view of its own
    }
}

namespace {

// Pixels whose scene textures (colour and position) are the same in `a` and `b` but whose images
// differ by more than `threshold` in some channel: what changed there came through the
// reflection map.
size_t reflected_changes(const SyntheticScene& a, const SyntheticScene& b, const ImageRGBA32F& ia,
                         const ImageRGBA32F& ib, double threshold) {
    size_t n = 0;
    for (size_t p = 0; p < ia.pixel_count(); ++p) {
        bool same_scene = true, differs = false;
        for (size_t k = p * 4; k < p * 4 + 4; ++k) {
            for (const char* t : {"scene_color", "scene_position"})
                same_scene = same_scene && a.textures.at(t).rgba[k] == b.textures.at(t).rgba[k];
            differs = differs || std::abs(ia.rgba[k] - ib.rgba[k]) > threshold;
        }
        if (same_scene && differs) ++n;
    }
    return n;
}

} // namespace

TEST_CASE("the_reflection_view_shows_its_buoy_in_the_planar_reflection", "[views]") {
    // The reflection view with and without its buoy: where the camera sees the same scene in
    // both, the planar reflection must still differ (the buoy's mirror image), the sky cube not.
    const uint32_t size = 96;
    SceneView no_buoy = *find_scene_view("reflection");
    no_buoy.standing_sphere.reset();
    const SyntheticScene with = make_synthetic_scene(size, size, *find_scene_view("reflection"));
    const SyntheticScene without = make_synthetic_scene(size, size, no_buoy);
    std::map<std::string, size_t> changes;
    for (const char* reflection : {"planar_projective", "sky_cubemap"}) {
        Variant v = accuracy_reference_variant();
        set_choice(v, "reflection", reflection);
        set_choice(v, "refraction", "none"); // nothing but the reflection samples off-pixel
        std::string error;
        const ImageRGBA32F a = cpu_variant_image(v, with, &error);
        const ImageRGBA32F b = cpu_variant_image(v, without, &error);
        INFO(error);
        REQUIRE(error.empty());
        changes[reflection] = reflected_changes(with, without, a, b, 1e-3);
    }
    std::printf("reflection view %ux%u: the buoy changes %zu pixels through the planar map, %zu "
                "through the sky cube\n",
                size, size, changes["planar_projective"], changes["sky_cubemap"]);
    CHECK(changes["planar_projective"] > size * size / 100);
    CHECK(changes["sky_cubemap"] == 0);
}

TEST_CASE("every_view_renders_alike_on_lavapipe_and_the_cpu", "[views][render]") {
    // The variant that reads most of the scene: every gold choice, planar reflection, the
    // refracted ray and shore foam. Bounds as in render_agreement (three_way_agreement_test).
    Variant v = accuracy_reference_variant();
    set_choice(v, "reflection", "planar_projective");
    set_choice(v, "refraction", "refracted_ray");
    set_choice(v, "foam", "shore");
    const VariantBuild build = build_variant(v);
    REQUIRE(build.ok());
    const RenderSettings settings{64, 64, 1, false};
    for (const SceneView& view : scene_views()) {
        INFO(view.name);
        const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height, view);
        const VariantRender r = render_variant(test::shared_runner(), build, scene, settings);
        REQUIRE(r.ok());
        std::printf("%-11s glsl-hlsl %.3g  gpu-cpu(float) %.3g / %.3g\n", view.name.c_str(),
                    r.glsl_vs_hlsl.max_abs, r.glsl_vs_cpu_float.max_abs,
                    r.hlsl_vs_cpu_float.max_abs);
        test::check_paths_agree(r, 5e-5);
    }
}

TEST_CASE("user_guide_names_every_view", "[views]") {
    // docs/user-guide.md, "Views".
    const std::string guide = test::user_guide_prose();
    for (const SceneView& v : scene_views()) {
        INFO(v.name);
        CHECK(guide.find("`" + v.name + "`") != std::string::npos);
    }
    CHECK(guide.find("--view") != std::string::npos);
}
