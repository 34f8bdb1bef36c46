// Every fresnel / extinction / specular / foam choice of this area rendered at 128x128 on
// lavapipe through both language paths and evaluated on the CPU, other axes at simple choices.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "render_agreement.h"
#include "shared_runner.h"
#include "watergen/eval/draw/variant_render.h"

using namespace watergen;

namespace {

Variant simple_variant(const std::string& fresnel, const std::string& extinction,
                       const std::string& specular, const std::string& foam) {
    std::string error;
    auto v = parse_variant_key(
        "fresnel=" + fresnel + ",extinction=" + extinction + ",specular=" + specular +
            ",foam=" + foam +
            ",reflection=none,refraction=none,normals=flat,waves=flat,shore=hard,precision=full,"
            "caustics=none",
        &error);
    INFO(error);
    REQUIRE(v.has_value());
    return *v;
}

std::vector<double> unit(double x, double y, double z) {
    const double l = std::sqrt(x * x + y * y + z * z);
    return {x / l, y / l, z / l};
}

// The synthetic scene with the sun low ahead of the camera, so the highlight of the flat sea is
// in view, and crest foam lowered to the still surface (e.z = -0.5 m, Hmax = 0.5 m: f = 0.5), so
// crest foam shows without waves.
SyntheticScene optics_scene(uint32_t size) {
    SyntheticScene scene = make_synthetic_scene(size, size);
    scene.uniforms["sun_direction"] = unit(0.1, -0.25, -1.0);
    scene.uniforms["foam_existence"] = {0.45, 4.35, -0.5};
    scene.uniforms["foam_max_height"] = {0.5};
    return scene;
}

ImageRGBA32F cpu_image(const Variant& v, const SyntheticScene& scene) {
    const WaterShader shader = build_water_shader(v);
    REQUIRE_FALSE(has_errors(shader.fragment.diagnostics()));
    const EvalResult r = evaluate_image(shader.fragment, "color", scene.eval_inputs(), scene.width,
                                        scene.height, EvalPrecision::Float);
    REQUIRE(r.ok());
    return to_image(r, scene.width, scene.height);
}

} // namespace

TEST_CASE("optics_choices_render_alike_in_glsl_hlsl_and_on_the_cpu", "[render]") {
    const RenderSettings settings{128, 128, 1, false};
    const SyntheticScene scene = optics_scene(settings.width);
    const std::vector<Variant> variants = {
        simple_variant("power", "linear", "toman_glare", "shore"),
        simple_variant("schlick", "exponential", "blinn_phong", "crest"),
        simple_variant("exact", "beer_lambert", "ggx_sun", "both")};
    for (const Variant& v : variants) {
        INFO(v.key());
        const VariantBuild build = build_variant(v);
        for (const auto& d : build.diagnostics)
            INFO(format_diagnostic(d));
        REQUIRE(build.ok());
        const VariantRender r = render_variant(test::shared_runner(), build, scene, settings);
        INFO(r.error);
        REQUIRE(r.ok());
        std::printf("%-60s glsl-hlsl %.3g  gpu-cpu(float) glsl %.3g hlsl %.3g  NaN/Inf %llu %llu\n",
                    v.key().c_str(), r.glsl_vs_hlsl.max_abs, r.glsl_vs_cpu_float.max_abs,
                    r.hlsl_vs_cpu_float.max_abs,
                    static_cast<unsigned long long>(r.glsl_vs_cpu_float.nan_inf_pixels),
                    static_cast<unsigned long long>(r.hlsl_vs_cpu_float.nan_inf_pixels));
        test::check_paths_agree(r, 1e-4);

        // The nodes under test show in the image: without the highlight, without the foam.
        Variant no_specular = v, no_foam = v;
        REQUIRE_FALSE(set_choice(no_specular, "specular", "none"));
        REQUIRE_FALSE(set_choice(no_foam, "foam", "none"));
        const double highlight = test::max_difference(r.cpu_float, cpu_image(no_specular, scene));
        const double foam = test::max_difference(r.cpu_float, cpu_image(no_foam, scene));
        std::printf("    largest change from the highlight %.3g, from the foam %.3g\n", highlight,
                    foam);
        CHECK(highlight > 0.05);
        CHECK(foam > 0.1);
    }
}

// The harbour_at_night preset's sun travels upwards (0.2, 0.3, 0.93): every specular choice
// must add exactly nothing (and no NaN) to the image.
TEST_CASE("specular_adds_nothing_with_the_sun_below_the_horizon", "[render][specular]") {
    SyntheticScene scene = optics_scene(64);
    scene.uniforms["sun_direction"] = {0.2, 0.3, 0.93};
    const ImageRGBA32F dark =
        cpu_image(simple_variant("schlick", "beer_lambert", "none", "none"), scene);
    for (const char* specular : {"toman_glare", "blinn_phong", "ggx_sun"}) {
        INFO(specular);
        const ImageRGBA32F image =
            cpu_image(simple_variant("schlick", "beer_lambert", specular, "none"), scene);
        for (float x : image.rgba)
            REQUIRE(std::isfinite(x));
        CHECK(image.rgba == dark.rgba);
    }
}
