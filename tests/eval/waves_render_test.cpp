// Every wave and normal choice rendered through both language paths on lavapipe at 128x128,
// against the CPU evaluator (float), over the synthetic scene with its wave textures.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "render_agreement.h"
#include "shared_runner.h"
#include "watergen/eval/draw/variant_render.h"
#include "watergen/ir/core/dsl.h"
#include "watergen/plan/variant_space.h"
#include "watergen/water/water_shader.h"

using namespace watergen;

namespace {

// WATERGEN_TEST_PNG_DIR=<dir> writes the GPU images for a look (not part of the checks).
void maybe_write_png(const ImageRGBA32F& image, const std::string& name) {
    const char* dir = std::getenv("WATERGEN_TEST_PNG_DIR");
    if (!dir) return;
    std::string error;
    write_png(std::string(dir) + "/" + name + ".png", image.width, image.height,
              tone_map_to_srgb8(image), &error);
}

// The other axes kept simple: no reflection, refraction, specular or foam.
Variant wave_variant(const std::string& waves, const std::string& normals) {
    std::string error;
    const auto v = parse_variant_key("waves=" + waves + ",normals=" + normals +
                                         ",reflection=none,refraction=none,specular=none,foam=none",
                                     &error);
    INFO(error);
    REQUIRE(v.has_value());
    REQUIRE_FALSE(check_constraints(*v).has_value());
    return *v;
}

// Pixels whose view ray points down (towards the water), and the rows above the horizon
// (0..4 at 128x128), which look up: set_water_column keeps those out of the water, so they
// must show the scene unchanged (the waves there would be evaluated ~1e6 m away).
std::vector<bool> looking_down(const SyntheticScene& scene) {
    const TextureData& p = scene.textures.at("scene_position"); // less the eye
    std::vector<bool> down(size_t(p.width) * p.height);
    for (size_t i = 0; i < down.size(); ++i)
        down[i] = p.rgba[i * 4 + 1] < 0.0f;
    return down;
}

size_t pixels_over(const ImageRGBA32F& a, const ImageRGBA32F& b, double bound) {
    size_t n = 0;
    for (size_t i = 0; i < size_t(a.width) * a.height; ++i) {
        bool over = false;
        for (int c = 0; c < 3; ++c)
            over = over || std::fabs(a.rgba[i * 4 + c] - b.rgba[i * 4 + c]) > bound;
        n += over;
    }
    return n;
}

struct Case {
    const char* waves;
    const char* normals;
};

} // namespace

TEST_CASE("every_wave_and_normal_choice_renders_the_same_on_glsl_hlsl_and_cpu", "[render][waves]") {
    const RenderSettings settings{128, 128, 0, false};
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    // Measured on lavapipe (Mesa 22.3.6), max |GPU - CPU float| over the whole image:
    // sum_of_sines 4.3e-6, gerstner 4.9e-6 (both normals), heightmap_march 2.7e-5,
    // heightmap_march_converged 1.9e-5, flat + detail_map 8.1e-7, heightmap_march + flat 4.3e-7.
    // The rows just under the horizon (surface points ~500 m away, phases ~500 rad) agree
    // because every wave model is band-limited to the pixel footprint in the surface search
    // (sum_over_waves, heightmap_height): without it a handful of grazing pixels landed on
    // different crests on the GPU and the CPU (measured up to 0.6).
    const Case cases[] = {
        {"sum_of_sines", "analytic"},
        {"gerstner", "analytic"},
        {"heightmap_march", "heightmap_diff"},
        {"heightmap_march_converged", "heightmap_diff"},
        {"gerstner", "detail_map"},
        {"flat", "detail_map"},
        {"heightmap_march", "flat"},
    };
    for (const Case& e : cases) {
        const Variant v = wave_variant(e.waves, e.normals);
        INFO(v.key());
        const VariantBuild build = build_variant(v);
        for (const auto& d : build.diagnostics)
            UNSCOPED_INFO(format_diagnostic(d));
        REQUIRE(build.ok());
        const VariantRender r = render_variant(test::shared_runner(), build, scene, settings);
        INFO(r.error);
        REQUIRE(r.ok());
        const double glsl = r.glsl_vs_cpu_float.max_abs, hlsl = r.hlsl_vs_cpu_float.max_abs;
        const size_t over = pixels_over(r.gpu_image[0], r.cpu_float, 1e-4);
        std::printf("waves=%-26s normals=%-15s glsl-hlsl %.3g  gpu-cpu(float) %.3g (%zu pixels "
                    "over 1e-4)  cpu %.0f ms\n",
                    e.waves, e.normals, r.glsl_vs_hlsl.max_abs, glsl, over, r.cpu_float_ms);
        // Upward rays show the scene exactly.
        std::vector<bool> up = looking_down(scene);
        up.flip();
        for (size_t i = 0; i < up.size(); ++i)
            if (up[i])
                for (int c = 0; c < 3; ++c)
                    REQUIRE(r.gpu_image[0].rgba[i * 4 + c] ==
                            scene.textures.at("scene_color").rgba[i * 4 + c]);
        maybe_write_png(r.gpu_image[0], std::string(e.waves) + "-" + e.normals);
        for (const auto& m : r.validation_messages)
            UNSCOPED_INFO(m);
        CHECK(r.validation_messages.empty());
        CHECK(r.glsl_vs_hlsl.max_abs <= 1e-6);
        CHECK(glsl <= 1e-4);
        CHECK(hlsl <= 1e-4);
        CHECK(r.glsl_vs_cpu_float.nan_inf_pixels == 0);
        CHECK(r.hlsl_vs_cpu_float.nan_inf_pixels == 0);
        CHECK(r.glsl_vs_cpu_float.reference_nan_inf_pixels == 0);
        CHECK_FALSE(is_degenerate(r.gpu_image[0]));
    }
}

TEST_CASE("a_nan_texel_in_a_wave_texture_stays_contained", "[render][waves][stress]") {
    // water-models.md: one NaN texel per input texture must not spread. A NaN height makes the
    // search level NaN, so is_water is false there (the scene shows through); a NaN in a
    // normal falls back through safe_normalize. No output pixel may be NaN.
    const RenderSettings settings{128, 128, 0, false};
    SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    for (const char* name : {"height_map", "detail_normal_map"}) {
        TextureData& t = scene.textures.at(name);
        for (int c = 0; c < 3; ++c)
            t.rgba[(size_t(20) * t.width + 37) * 4 + c] = NAN;
    }
    for (const auto& [waves, normals] :
         {std::pair{"heightmap_march", "heightmap_diff"}, std::pair{"gerstner", "detail_map"}}) {
        const VariantBuild build = build_variant(wave_variant(waves, normals));
        REQUIRE(build.ok());
        const VariantRender r = render_variant(test::shared_runner(), build, scene, settings);
        INFO(waves << " " << normals << " " << r.error);
        REQUIRE(r.ok());
        CHECK(r.glsl_vs_cpu_float.nan_inf_pixels == 0);
        CHECK(r.hlsl_vs_cpu_float.nan_inf_pixels == 0);
        CHECK(r.glsl_vs_cpu_float.reference_nan_inf_pixels == 0);
        CHECK(r.validation_messages.empty());
    }
}

TEST_CASE("lavapipe_derivatives_are_fine_like_the_cpu_evaluators_quads", "[render][waves]") {
    // The derivative tangent frame reads ddx/ddy. The CPU evaluator differences per row and per
    // column of each 2x2 quad ("fine"); a GPU computing "coarse" derivatives (one per quad)
    // would disagree in the quad's second row and column. Measured on lavapipe: identical, and
    // even dFdxCoarse is per row there.
    WaterShader shader;
    shader.variant = default_variant();
    Graph& g = shader.fragment;
    Expr uv = varying(g, "v_uv", Type::Vec2);
    // Quadratic in uv: fine and coarse differences differ by the cross term.
    Expr f = (uv.x() * uv.x() * 3.0 + uv.y() * uv.y() * 5.0 + uv.x() * uv.y() * 7.0) * 100.0;
    g.set_output("color",
                 vec4(ddx(f), ddy(f), ddx(uv.x() * uv.y() * 100.0), constant(g, 1.0)).id());
    const VariantBuild build = build_shader(std::move(shader));
    REQUIRE(build.ok());
    const RenderSettings settings{64, 64, 0, false};
    const SyntheticScene scene = make_synthetic_scene(64, 64);
    const VariantRender r = render_variant(test::shared_runner(), build, scene, settings);
    INFO(r.error);
    REQUIRE(r.ok());
    // Differences of values up to 1500 computed in float on both sides: a few ulps of 1500
    // (1.2e-4 each). A coarse GPU would be off by the cross term, 700 / 64^2 = 0.17.
    CHECK(r.glsl_vs_cpu_float.max_abs <= 1e-3);
    CHECK(r.hlsl_vs_cpu_float.max_abs <= 1e-3);
    CHECK(r.validation_messages.empty());
}

TEST_CASE("wave_models_agree_with_the_cpu_at_256x256_and_a_non_power_of_two_size",
          "[render][waves]") {
    // 128x128 (above) is not special: at 256x256 the Gerstner search used to end in a
    // crest-trough 2-cycle of its Newton steps on a few grazing pixels (one fixed-point step
    // per search step left the grid point metres behind, and no bracket stopped the cycle),
    // where float rounding picked the end of the cycle: 0.0445 at (61, 38). At 192x144 the
    // pixel-centre uv is inexact in float, so bilinear sampling blends neighbouring scene
    // texels by ~1e-7: that alone must not create large errors either.
    const Case cases[] = {
        {"sum_of_sines", "analytic"},
        {"gerstner", "analytic"},
        {"heightmap_march", "heightmap_diff"},
        {"heightmap_march_converged", "heightmap_diff"},
    };
    for (const auto& [width, height] : {std::pair{256u, 256u}, std::pair{192u, 144u}}) {
        const RenderSettings settings{width, height, 0, false};
        const SyntheticScene scene = make_synthetic_scene(width, height);
        for (const Case& e : cases) {
            const Variant v = wave_variant(e.waves, e.normals);
            INFO(v.key() << " at " << width << "x" << height);
            const VariantBuild build = build_variant(v);
            REQUIRE(build.ok());
            const VariantRender r = render_variant(test::shared_runner(), build, scene, settings);
            INFO(r.error);
            REQUIRE(r.ok());
            const size_t over = pixels_over(r.gpu_image[0], r.cpu_float, 1e-4);
            std::printf("%ux%u waves=%-26s normals=%-15s glsl-hlsl %.3g  gpu-cpu(float) max %.3g "
                        "at (%u, %u) rmse %.3g (%zu pixels over 1e-4)\n",
                        width, height, e.waves, e.normals, r.glsl_vs_hlsl.max_abs,
                        r.glsl_vs_cpu_float.max_abs, r.glsl_vs_cpu_float.max_abs_location.x,
                        r.glsl_vs_cpu_float.max_abs_location.y, r.glsl_vs_cpu_float.rmse, over);
            test::check_paths_agree(r, 1e-4);
            CHECK(r.glsl_vs_cpu_float.rmse <= 1e-5);
        }
    }
}
