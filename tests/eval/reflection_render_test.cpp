// Every reflection and refraction choice rendered through both language paths on lavapipe at
// 128x128 over the synthetic scene, against the CPU evaluator (float); and lavapipe's cube
// filtering at face edges and corners against the evaluator's.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "render_agreement.h"
#include "shared_runner.h"
#include "watergen/eval/draw/variant_render.h"
#include "watergen/ir/core/dsl.h"
#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/plan/variant_space.h"

using namespace watergen;

namespace {

Variant optics_variant(const std::string& choices) {
    std::string error;
    const auto v =
        parse_variant_key("waves=flat,normals=flat,specular=none,foam=none," + choices, &error);
    INFO(error);
    REQUIRE(v.has_value());
    REQUIRE_FALSE(check_constraints(*v).has_value());
    return *v;
}

} // namespace

TEST_CASE("every_reflection_and_refraction_choice_renders_the_same_on_glsl_hlsl_and_cpu",
          "[render][reflection]") {
    const RenderSettings settings{128, 128, 0, false};
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    // Measured max |GPU - CPU float| over linear rgb at 128x128 (see the printed figures):
    // every texture lookup here is bilinear between texels (the sky cube along reflected rays,
    // the reflection map at 0.5 + (uv - 0.5) / 1.5, the Fourier maps at surface_point.xz, the
    // scene colour at refracted uvs), unlike the texel-centre lookups of the other axes.
    const char* cases[] = {
        "reflection=sky_cubemap,refraction=none",
        "reflection=planar_projective,refraction=none",
        "reflection=fourier_horizon,refraction=none",
        "reflection=none,refraction=screen_distort",
        "reflection=none,refraction=refracted_ray",
        "reflection=planar_projective,refraction=refracted_ray,precision=half",
        "reflection=fourier_horizon,refraction=screen_distort,precision=half",
    };
    for (const char* choices : cases) {
        const Variant v = optics_variant(choices);
        INFO(v.key());
        const VariantBuild build = build_variant(v);
        for (const auto& d : build.diagnostics)
            UNSCOPED_INFO(format_diagnostic(d));
        REQUIRE(build.ok());
        const VariantRender r = render_variant(test::shared_runner(), build, scene, settings);
        INFO(r.error);
        REQUIRE(r.ok());
        std::printf("%-70s glsl-hlsl %.3g  gpu-cpu(float) %.3g at (%u,%u)  first draw %.0f ms\n",
                    choices, r.glsl_vs_hlsl.max_abs, r.glsl_vs_cpu_float.max_abs,
                    r.glsl_vs_cpu_float.max_abs_location.x, r.glsl_vs_cpu_float.max_abs_location.y,
                    r.gpu[0].first_draw_ms);
        test::check_paths_agree(r, 1e-4);
    }
}

TEST_CASE("normal_displaced_lookups_render_the_same_on_glsl_hlsl_and_cpu", "[render][reflection]") {
    // Flat normals leave 001's displacement and 000's screen distortion at zero; the detail
    // normal map (normals axis, core/nodes/normals.cpp) moves every lookup off the texel grid.
    const RenderSettings settings{128, 128, 0, false};
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    for (const char* choices : {"reflection=planar_projective,refraction=screen_distort",
                                "reflection=sky_cubemap,refraction=refracted_ray",
                                "reflection=fourier_horizon,refraction=screen_distort"}) {
        std::string error;
        const auto v = parse_variant_key(
            std::string("waves=flat,normals=detail_map,specular=none,foam=none,") + choices,
            &error);
        INFO(error);
        REQUIRE(v.has_value());
        INFO(v->key());
        const VariantBuild build = build_variant(*v);
        for (const auto& d : build.diagnostics)
            UNSCOPED_INFO(format_diagnostic(d));
        REQUIRE(build.ok());
        const VariantRender r = render_variant(test::shared_runner(), build, scene, settings);
        INFO(r.error);
        REQUIRE(r.ok());
        std::printf("normals=detail_map %-55s glsl-hlsl %.3g  gpu-cpu(float) %.3g at (%u,%u)\n",
                    choices, r.glsl_vs_hlsl.max_abs, r.glsl_vs_cpu_float.max_abs,
                    r.glsl_vs_cpu_float.max_abs_location.x, r.glsl_vs_cpu_float.max_abs_location.y);
        test::check_paths_agree(r, 1e-4);
    }
}

TEST_CASE("lavapipe_filters_cube_maps_like_the_cpu_evaluator_across_edges_and_corners",
          "[render][cube]") {
    // A custom pass: 3 x 2 tiles, tile k looks at cube face k through face coordinates
    // sc, tc in [-1.2, 1.2], so every edge and corner of every face is crossed. Texels are
    // deliberately not smooth (each differs from its neighbours by up to 0.9), so a wrong
    // neighbour across an edge, a clamped edge or a different corner rule shows as ~0.1.
    constexpr uint32_t n = 8, w = 192, h = 128;
    TextureData cube{n, n, 6, std::vector<float>(6 * n * n * 4, 1.0f)};
    for (uint32_t f = 0; f < 6; ++f)
        for (uint32_t j = 0; j < n; ++j)
            for (uint32_t i = 0; i < n; ++i) {
                const size_t texel = (size_t(f) * n + j) * n + i;
                cube.rgba[texel * 4 + 0] =
                    static_cast<float>(((i * 7 + j * 3 + f * 5) % 10) / 10.0);
                cube.rgba[texel * 4 + 1] = static_cast<float>(f / 6.0 + i / 64.0);
                cube.rgba[texel * 4 + 2] = static_cast<float>(j / 8.0);
            }
    WaterShader shader{parse_variant_key("", nullptr).value(), "", Graph{}};
    Graph& g = shader.fragment;
    {
        OriginScope scope(g, "cube_filter_probe");
        Expr uv = varying(g, "v_uv", Type::Vec2);
        Expr tiles = uv * constant(g, {3.0, 2.0});
        Expr tile = floor(tiles);
        Expr k = tile.x() + 3.0 * tile.y();
        Expr local = fract(tiles) * 2.4 - 1.2;
        Expr dir;
        for (int f = 5; f >= 0; --f) {
            double a[3], b[3], c[3];
            cube_face_direction(f, 0.5, 0.5, a); // centre
            cube_face_direction(f, 1.0, 0.5, b); // sc = 1
            cube_face_direction(f, 0.5, 1.0, c); // tc = 1
            Expr centre = constant(g, {a[0], a[1], a[2]});
            Expr along_s = constant(g, {b[0] - a[0], b[1] - a[1], b[2] - a[2]});
            Expr along_t = constant(g, {c[0] - a[0], c[1] - a[1], c[2] - a[2]});
            Expr d = centre + along_s * local.x() + along_t * local.y();
            // Tile k's face by weights, not a chain of selects: glslang turns a nested ternary
            // inside texture()'s argument list into branches and spirv-val then rejects the
            // OpSampledImage made before them (reported to the lead).
            Expr weight = step(constant(g, f - 0.5), k) - step(constant(g, f + 0.5), k);
            dir = f == 5 ? d * weight : dir + d * weight;
        }
        Expr texel = sample(texture(g, {"probe_cube", Type::TextureCube, "", ""}), dir);
        g.set_output("color", vec4(texel.xyz(), constant(g, 1.0)).id());
    }
    const VariantBuild build = build_shader(std::move(shader));
    for (const auto& d : build.diagnostics)
        UNSCOPED_INFO(format_diagnostic(d));
    REQUIRE(build.ok());
    SyntheticScene scene;
    scene.width = w;
    scene.height = h;
    scene.textures["probe_cube"] = cube;
    const VariantRender r = render_variant(test::shared_runner(), build, scene, {w, h, 0, false});
    INFO(r.error);
    REQUIRE(r.ok());
    std::printf("cube filtering probe: glsl-hlsl %.3g  gpu-cpu(float) %.3g at (%u,%u)\n",
                r.glsl_vs_hlsl.max_abs, r.glsl_vs_cpu_float.max_abs,
                r.glsl_vs_cpu_float.max_abs_location.x, r.glsl_vs_cpu_float.max_abs_location.y);
    test::check_paths_agree(r, 1e-5);
}
