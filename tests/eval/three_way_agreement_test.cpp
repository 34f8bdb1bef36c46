#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "shared_runner.h"
#include "watergen/eval/draw/variant_render.h"
#include "watergen/plan/covering_array.h"

using namespace watergen;

// Every variant of the covering set through both language paths on lavapipe, against the CPU
// evaluator in float and in double, at 512x512 (users render at 512x512 and up; a bound that
// held at 256x256 failed here before the GGX lobe stopped jumping at grazing N.V).
TEST_CASE("glsl_hlsl_and_cpu_agree_for_every_variant_at_512", "[render]") {
    RenderSettings settings{512, 512, 1, true};
    settings.float_bound = true;
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    for (const Variant& v : pairwise_covering_variants()) {
        INFO(v.key());
        const VariantBuild build = build_variant(v);
        REQUIRE(build.ok());
        const VariantRender r = render_variant(test::shared_runner(), build, scene, settings);
        REQUIRE(r.ok());
        const Agreement &g = r.agreement[0], &h = r.agreement[1];
        std::printf("%-44s glsl-hlsl %.3g  gpu-cpu(float) %.3g / %.3g  gpu-cpu(double) %.3g  "
                    "over 5e-5 %llu, over bound %llu, max bound %.3g\n",
                    v.key().c_str(), r.glsl_vs_hlsl.max_abs, r.glsl_vs_cpu_float.max_abs,
                    r.hlsl_vs_cpu_float.max_abs, r.glsl_vs_cpu_double.max_abs,
                    static_cast<unsigned long long>(g.over_tolerance),
                    static_cast<unsigned long long>(g.over_bound), g.max_bound);
        CHECK(r.validation_messages.empty());
        // Both paths run the same IR through spirv-opt; measured: bit-identical (0). The bound
        // leaves room for a front end ordering one operation differently (a few float ulps).
        CHECK(r.glsl_vs_hlsl.max_abs <= 1e-6);
        // Every pixel within 5e-5 of the CPU float image plus the float error expected there
        // (twice the spread of the double image under one-ulp moves of every operation two
        // float evaluations can round differently). Measured at 512x512 after the GGX fix: no
        // pixel over it; at most 6 pixels of a variant over 5e-5 alone (0.0023%), all in far,
        // grazing water where the surface point's float rounding moves the waves' phases.
        // One pixel may step: the Blinn-Phong lobe ends at the terminator (N.L = 0, specular.cpp
        // sun_lights), a step of the model that the bound's four ulp-perturbed runs sample only
        // by chance, and lavapipe's sin and cos (not rounded like the CPU's) move N.L by more
        // than an ulp. Measured with the shader in the eye's frame (1 m cell): one pixel of
        // schlick/beer_lambert/blinn_phong/both/sky_cubemap/screen_distort/analytic/gerstner/
        // soft/full/photon_splat, (185, 62), 5.87e-4 from CPU float, bound 1.03e-5, lit on the
        // GPU only; with specular=none it is within its bound. `watergen render` of that key.
        CHECK(g.over_bound <= 1);
        CHECK(h.over_bound <= 1);
        CHECK(g.over_tolerance <= 26); // 1e-4 of the pixels
        // The bound explains, it does not excuse: measured at most 0.0323 at a pixel.
        // Against double: measured at most 2.59e-3 (sum of sines at half precision, far water:
        // the GPU and the CPU float image agree there, both float roundings of the same phases).
        // A scene unprojected from the depth buffer has the shoreline as a float rounding: where
        // the seabed meets the water level, the float and double unprojections of a texel fall
        // on either side of it (water or sand, a jump of up to 0.2), and the bound says so. Such
        // pixels lie on the shoreline, a line across the image: at most two per column
        // (measured at most 509 in a variant); of them, at most 1e-4 of the image apart from
        // double by over 5e-3 (measured at most 9).
        size_t wide_bound = 0, far_from_double = 0;
        for (size_t p = 0; p < r.float_bound.size(); ++p) {
            wide_bound += r.float_bound[p] > 0.05f;
            double apart = 0;
            for (size_t c = 0; c < 3; ++c)
                apart = std::max(apart, double(std::fabs(r.gpu_image[0].rgba[p * 4 + c] -
                                                         r.cpu_double.rgba[p * 4 + c])));
            far_from_double += apart > 5e-3;
        }
        std::printf("  pixels with a bound over 0.05: %zu, over 5e-3 from double: %zu\n",
                    wide_bound, far_from_double);
        if (v.choice("scene_input") == "position_texture") {
            CHECK(g.max_bound <= 0.05);
            CHECK(r.glsl_vs_cpu_double.max_abs <= 5e-3);
        } else {
            CHECK(wide_bound <= 2u * 512u);
            CHECK(far_from_double <= 26u);
        }
        CHECK(r.gpu_image[0].rgba.size() == 512u * 512u * 4u);
        CHECK(r.glsl_vs_cpu_float.nan_inf_pixels == 0);
        CHECK(r.hlsl_vs_cpu_float.nan_inf_pixels == 0);
        CHECK(r.glsl_vs_cpu_float.reference_nan_inf_pixels == 0);
        CHECK_FALSE(is_degenerate(r.gpu_image[0]));
    }
}
