// The depth-buffer scene input (water/nodes/scene_input.h): the scene's world position
// unprojected from a depth buffer under each of an engine's conventions, drawn on lavapipe
// through both languages and checked against the CPU reference; the same image as the
// world-position texture gives; and a wrong convention caught.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "render_agreement.h"
#include "shared_runner.h"
#include "watergen/eval/draw/variant_render.h"

using namespace watergen;

namespace {

// Every axis that reads the scene's position: the water column (extinction, shore, foam),
// the refracted ray's projection, the caustics texture at the bottom and Gerstner waves.
Variant variant(const std::string& scene_input) {
    std::string error;
    auto v = parse_variant_key(
        "fresnel=exact,extinction=beer_lambert,specular=ggx_sun,foam=shore,"
        "reflection=sky_cubemap,refraction=refracted_ray,normals=analytic,waves=gerstner,"
        "shore=soft,precision=full,caustics=texture,scene_input=" +
            scene_input,
        &error);
    INFO(error);
    REQUIRE(v.has_value());
    return *v;
}

struct Conventions {
    bool reversed, gl_range, y_up, camera_relative;
    std::string name() const {
        return std::string(reversed ? "reversed Z" : "standard Z") +
               (gl_range ? ", NDC z -1..1" : ", NDC z 0..1") + (y_up ? ", y up" : ", y down") +
               (camera_relative ? ", camera-relative" : ", world");
    }
};

SyntheticScene scene_with(uint32_t size, const Conventions& k) {
    SyntheticScene scene = make_synthetic_scene(size, size);
    scene.uniforms["scene_depth_reversed"] = {k.reversed ? 1.0 : 0.0};
    scene.uniforms["scene_depth_gl_range"] = {k.gl_range ? 1.0 : 0.0};
    scene.uniforms["scene_ndc_y_up"] = {k.y_up ? 1.0 : 0.0};
    scene.uniforms["scene_camera_relative"] = {k.camera_relative ? 1.0 : 0.0};
    add_depth_inputs(scene);
    return scene;
}

ImageRGBA32F cpu_image(const Graph& g, const SyntheticScene& scene, EvalPrecision precision) {
    const EvalResult r =
        evaluate_image(g, "color", scene.eval_inputs(), scene.width, scene.height, precision);
    REQUIRE(r.ok());
    return to_image(r, scene.width, scene.height);
}

VariantBuild checked_build(const Variant& v) {
    VariantBuild build = build_variant(v);
    for (const auto& d : build.diagnostics)
        UNSCOPED_INFO(format_diagnostic(d));
    REQUIRE(build.ok());
    return build;
}

constexpr uint32_t kSize = 64;

} // namespace

TEST_CASE("depth_buffer_variants_agree_with_the_cpu_under_every_convention", "[render]") {
    const VariantBuild build = checked_build(variant("depth_buffer"));
    const Graph& truth_graph = build_water_shader(variant("position_texture")).fragment;
    const ImageRGBA32F truth =
        cpu_image(truth_graph, make_synthetic_scene(kSize, kSize), EvalPrecision::Double);
    RenderSettings settings{kSize, kSize, 1, true};
    settings.float_bound = true;
    for (int bits = 0; bits < 16; ++bits) {
        const Conventions k{(bits & 1) != 0, (bits & 2) != 0, (bits & 4) != 0, (bits & 8) != 0};
        INFO(k.name());
        const SyntheticScene scene = scene_with(kSize, k);
        const VariantRender r = render_variant(test::shared_runner(), build, scene, settings);
        INFO(r.error);
        REQUIRE(r.ok());
        // GLSL = HLSL, no NaN, within 5e-5 plus the float error expected at each pixel (the
        // render command's check). The bound is the conventions' own: standard Z unprojects
        // 1 - d, which float holds to 6e-8 / (1 - d) relative, so its far water pixels get a
        // bound near 0.1 where reversed Z stays near 4e-5.
        test::check_paths_agree(r, 1.0);
        CHECK(r.agreement[0].holds());
        CHECK(r.agreement[1].holds());
        CHECK(r.agreement[0].over_bound == 0);
        CHECK(r.agreement[1].over_bound == 0);
        // The same picture as the world-position texture: the CPU reference in double of both,
        // apart only by the depth buffer's float rounding of each texel's distance (2^-24
        // relative in reversed Z; in standard Z 2^-24 / (1 - d), 1 - d = 1e-3 at 100 m).
        const double apart = test::max_difference(r.cpu_double, truth);
        CHECK(apart <= (k.reversed ? 1e-4 : 1e-3));
        std::printf("%-55s glsl-hlsl %.3g  gpu-cpu(float) %.3g  bound %.3g  vs position "
                    "texture %.3g\n",
                    k.name().c_str(), r.glsl_vs_hlsl.max_abs, r.glsl_vs_cpu_float.max_abs,
                    r.agreement[0].max_bound, apart);
    }
}

TEST_CASE("a_flipped_z_convention_is_caught", "[render]") {
    // The engine wrote a reversed-Z depth buffer; the shader is told standard Z. The CPU
    // reference reads the buffer as it was written, the GPU as it was told.
    const VariantBuild build = checked_build(variant("depth_buffer"));
    const Graph& g = build.shader.fragment;
    const SyntheticScene truth = scene_with(kSize, {true, false, false, false});
    SyntheticScene told = truth;
    told.uniforms["scene_depth_reversed"] = {0.0}; // the depth texture stays reversed
    RenderSettings gpu_only{kSize, kSize, 1, false, false};
    const ImageRGBA32F reference = cpu_image(g, truth, EvalPrecision::Float);
    const EvalResult d =
        evaluate_image(g, "color", truth.eval_inputs(), kSize, kSize, EvalPrecision::Double);
    REQUIRE(d.ok());
    std::string error;
    const std::vector<float> bound = float_bound(g, truth.eval_inputs(), kSize, kSize, d, error);
    REQUIRE(error.empty());
    for (const SyntheticScene* scene :
         std::initializer_list<const SyntheticScene*>{&truth, &told}) {
        const VariantRender r = render_variant(test::shared_runner(), build, *scene, gpu_only);
        INFO(r.error);
        REQUIRE(r.ok());
        for (size_t i = 0; i < 2; ++i) {
            const Agreement a =
                check_agreement(r.gpu_image[i], reference, bound, kAgreementTolerance);
            std::printf("%s, %s: %llu of %llu pixels over 5e-5 plus their bound\n",
                        scene == &truth ? "told right" : "told flipped", i ? "hlsl" : "glsl",
                        static_cast<unsigned long long>(a.over_bound),
                        static_cast<unsigned long long>(a.compared));
            if (scene == &truth) {
                CHECK(a.over_bound == 0);
            } else {
                // Every water pixel moves: more than a tenth of the image fails.
                CHECK(a.over_bound > a.compared / 10);
                CHECK_FALSE(a.holds());
            }
        }
    }
}
