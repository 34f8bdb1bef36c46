// The geometry axis drawn on lavapipe: mesh and tessellated variants over the runtime
// library's clipmap grid (watergen/runtime/water_grid.h), through both languages, against the
// exact surface (the screen pass of the same choices, evaluated in double); the tessellator at
// factor 1 against the mesh over the same cells; tess_max past 64 drawing what the shader's
// clamp gives; which way the triangles wind; the runner's refusals.
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>

#include "geometry_variant.h"
#include "shared_runner.h"
#include "watergen/eval/draw/mesh_render.h"
#include "watergen/eval/draw/variant_render.h"
#include "watergen/ir/core/dsl.h"
#include "watergen/ir/emit/vertex_emitter.h"

using namespace watergen;
using watergen::test::geometry_variant;

namespace {

VariantBuild geometry_build(const std::string& geometry, const std::string& model) {
    VariantBuild b = build_variant(geometry_variant(geometry, model));
    for (const auto& d : b.diagnostics)
        UNSCOPED_INFO(format_diagnostic(d));
    REQUIRE(b.ok());
    return b;
}

// A grid for 128 x 128 tests: 0.5 m cells near the eye, 6 levels out to 256 m.
MeshRenderSettings small_settings(uint32_t size = 128) {
    MeshRenderSettings s;
    s.width = s.height = size;
    s.grid = {0.5, 16, 6};
    return s;
}

// Pixels a fragment wrote (the clear leaves alpha 0).
size_t covered_pixels(const RenderResult& r) {
    size_t covered = 0;
    for (size_t p = 0; p < r.rgba.size() / 4; ++p)
        covered += r.rgba[p * 4 + 3] != 0.0f;
    return covered;
}

size_t differing_pixels(const ImageRGBA32F& a, const ImageRGBA32F& b) {
    size_t n = 0;
    for (size_t p = 0; p < size_t(a.width) * a.height; ++p)
        for (size_t c = 0; c < 4; ++c)
            if (a.rgba[p * 4 + c] != b.rgba[p * 4 + c]) {
                ++n;
                break;
            }
    return n;
}

void require_drawn(const MeshRender& r) {
    INFO(r.error);
    REQUIRE(r.ok());
    for (const auto& m : r.validation_messages)
        UNSCOPED_INFO(m);
    CHECK(r.validation_messages.empty());
}

} // namespace

TEST_CASE("mesh_and_tessellated_variants_render_identically_from_glsl_and_hlsl",
          "[render][waves][mesh][tessellation]") {
    REQUIRE(test::shared_runner().device_info().tessellation_shader);
    CHECK(test::shared_runner().device_info().max_tessellation_level >= 64u);
    const SyntheticScene scene = make_synthetic_scene(128, 128);
    for (const char* geometry : {"mesh", "tessellated"})
        for (const char* model : {"sum_of_sines", "gerstner"}) {
            INFO(geometry << " " << model);
            const VariantBuild build = geometry_build(geometry, model);
            MeshRenderSettings settings = small_settings();
            // Patches of 2 m, cut up to 16 times within tess_scale = 40 m.
            if (std::string(geometry) == "tessellated") settings.grid = {2.0, 16, 4};
            const MeshRender r = render_mesh_variant(test::shared_runner(), build, scene, settings);
            require_drawn(r);
            std::printf("%-11s %-13s glsl-hlsl max abs %.3g, %zu of 16384 pixels covered, %llu "
                        "vertices, %llu primitives\n",
                        geometry, model, r.glsl_vs_hlsl.max_abs, size_t(r.covered),
                        static_cast<unsigned long long>(r.vertices),
                        static_cast<unsigned long long>(r.primitives));
            // Same IR, same spirv-opt, same rasteriser: bit-identical, as the screen pass is.
            CHECK(r.glsl_vs_hlsl.max_abs == 0.0);
            CHECK(r.glsl_vs_hlsl.nan_inf_pixels == 0);
            CHECK(covered_pixels(r.gpu[1]) == r.covered);
            // The water below the horizon (about two thirds of the beach view) is covered.
            CHECK(r.covered > 16384u / 2);
            CHECK_FALSE(is_degenerate(r.gpu_image[0]));
            if (const char* dir = std::getenv("WATERGEN_TEST_PNG_DIR")) {
                std::string error;
                write_png(std::string(dir) + "/" + geometry + "-" + model + ".png", 128, 128,
                          tone_map_to_srgb8(r.gpu_image[0]), &error);
            }
        }
}

TEST_CASE("a_denser_grid_comes_closer_to_the_exact_surface", "[render][waves][mesh]") {
    // The mesh against the screen pass of the same choices with its search run to convergence,
    // in double: the grid's geometric error. Its density at a distance d is about
    // ring_cells / d cells per metre, so the rings set the error away from the eye.
    const SyntheticScene scene = make_synthetic_scene(128, 128);
    const VariantBuild build = geometry_build("mesh", "gerstner");
    RenderSettings settings{128, 128, 0, true, false};
    std::vector<double> p99;
    for (uint32_t rings : {16u, 64u}) {
        settings.grid = {0.5, rings, 9};
        const VariantRender r = render_variant(test::shared_runner(), build, scene, settings);
        INFO(r.error);
        REQUIRE(r.ok());
        CHECK(r.glsl_vs_hlsl.max_abs == 0.0);
        std::printf("mesh gerstner, %u rings: against the exact surface max abs %.3g, rmse "
                    "%.3g, CIEDE2000 mean %.3g p99 %.3g\n",
                    rings, r.glsl_vs_cpu_double.max_abs, r.glsl_vs_cpu_double.rmse,
                    r.glsl_vs_cpu_double.ciede2000_mean, r.glsl_vs_cpu_double.ciede2000_p99);
        p99.push_back(r.glsl_vs_cpu_double.ciede2000_p99);
        CHECK(r.glsl_vs_cpu_double.nan_inf_pixels == 0);
    }
    // Measured at 128 x 128: CIEDE2000 p99 14.1 at 16 rings, 3.85 at 64.
    CHECK(p99[1] < p99[0] / 2);
    CHECK(p99[1] < 5.0);
}

TEST_CASE("morph_weights_rise_to_1_within_a_level_and_restart_at_0_on_the_next", "[mesh]") {
    // Up the centre column the ground point recedes from the eye: within a level the morph
    // weight only grows, a level's outer cells are fully morphed (water_grid.h: t = 1 with a
    // cell of margin) and the next level's inner cells still (t = 0 with three cells of
    // margin), so the weight only ever falls from 1 to 0; past the grid or above the horizon
    // it is -1.
    const uint32_t n = 256;
    const SyntheticScene scene = make_synthetic_scene(n, n);
    const WaterGridDesc desc{0.5, 16, 6};
    const WaterGrid grid = scene_grid(scene, desc, false, n, n);
    const std::vector<double> t = morph_weights(scene, desc, grid, n, n);
    REQUIRE(t.size() == size_t(n) * n);
    for (double w : t)
        CHECK((w == -1.0 || (w >= 0.0 && w <= 1.0)));
    size_t falls = 0, blending = 0;
    double previous = t[size_t(n - 1) * n + n / 2];
    CHECK(previous == 0.0); // the bottom row sees the ground just ahead of the eye
    for (uint32_t y = n - 1; y-- > 0;) {
        const double w = t[size_t(y) * n + n / 2];
        blending += w > 0.0 && w < 1.0;
        if (w == -1.0) break; // past the grid
        if (w < previous) {
            INFO("row " << y);
            CHECK(previous == 1.0);
            CHECK(w == 0.0);
            ++falls;
        }
        previous = w;
    }
    CHECK(falls >= 2); // the column crosses at least three levels
    CHECK(blending > 0);
    CHECK(t[n / 2] == -1.0); // the top row: sky above the beach
}

TEST_CASE("tessellated_at_factor_1_matches_the_mesh_over_the_same_cells",
          "[render][waves][mesh][tessellation]") {
    const SyntheticScene scene = make_synthetic_scene(128, 128);
    const VariantBuild tess = geometry_build("tessellated", "gerstner");
    const VariantBuild mesh = geometry_build("mesh", "gerstner");
    MeshRenderSettings settings = small_settings();
    const MeshRender m = render_mesh_variant(test::shared_runner(), mesh, scene, settings);
    require_drawn(m);
    // tess_max 1: every factor 1, each patch one quad of two triangles over its corners.
    settings.overrides = {{"tess_max", {1}}};
    const MeshRender t = render_mesh_variant(test::shared_runner(), tess, scene, settings);
    require_drawn(t);
    const ImageErrorStats e = compare_images(t.gpu_image[0], m.gpu_image[0]);
    std::printf("tessellated at factor 1 vs mesh (gerstner): max abs %.3g, %zu differing "
                "pixels, covered %llu vs %llu\n",
                e.max_abs, differing_pixels(t.gpu_image[0], m.gpu_image[0]),
                static_cast<unsigned long long>(t.covered),
                static_cast<unsigned long long>(m.covered));
    CHECK(t.glsl_vs_hlsl.max_abs == 0.0);
    // The same triangles: the tessellator splits each quad along the diagonal b-c the grid's
    // triangles (a, b, c), (b, d, c) share. The same pixels covered; values apart by float
    // rounding of the interpolation alone.
    CHECK(t.covered == m.covered);
    CHECK(e.max_abs <= 1e-5);
}

TEST_CASE("tess_max_out_of_range_draws_what_the_shader_clamp_gives",
          "[render][waves][mesh][tessellation]") {
    const SyntheticScene scene = make_synthetic_scene(64, 64);
    const VariantBuild build = geometry_build("tessellated", "gerstner");
    // The 16 patches of 4 m nearest the eye (the grid's draw order ends with them): factor 64
    // on every patch of a whole grid is millions of triangles, minutes on lavapipe.
    const WaterGrid grid = water_grid({4.0, 16, 1}, 0.0, -7.0, GridTopology::Patches);
    MeshData patches = grid_mesh(grid);
    patches.indices.erase(patches.indices.begin(), patches.indices.end() - 16 * 4);
    auto draw = [&](double tess_max) {
        std::map<std::string, std::vector<double>> values = mesh_values(scene, grid, 64, 64);
        values["tess_scale"] = {1e4};
        values["tess_max"] = {tess_max};
        std::array<ImageRGBA32F, 2> image;
        for (size_t i = 0; i < 2; ++i) {
            const RenderResult r = test::shared_runner().render(
                mesh_render_job(build.languages[i], scene, patches, values, 64, 64, 0));
            INFO(r.error);
            REQUIRE(r.ok);
            image[i] = ImageRGBA32F{64, 64, r.rgba};
        }
        CHECK(compare_images(image[0], image[1]).max_abs == 0.0);
        return image[0];
    };
    // 100 is refused by no one before the shader: it draws exactly what 64 draws.
    const ImageRGBA32F at_64 = draw(64), at_100 = draw(100);
    CHECK(differing_pixels(at_64, at_100) == 0u);
    // 0 draws what 1 draws (never a culled patch).
    const ImageRGBA32F at_1 = draw(1), at_0 = draw(0);
    CHECK(differing_pixels(at_1, at_0) == 0u);
    // And the factor matters: 64 and 1 differ.
    const size_t differing = differing_pixels(at_64, at_1);
    std::printf("tess_max 64 vs 1 over 16 patches of 4 m: %zu of 4096 pixels differ\n", differing);
    CHECK(differing > 0u);
}

TEST_CASE("grid_triangles_and_tessellated_triangles_face_the_eye_counter_clockwise",
          "[render][waves][mesh][tessellation]") {
    const SyntheticScene scene = make_synthetic_scene(64, 64);
    for (const char* geometry : {"mesh", "tessellated"}) {
        INFO(geometry);
        const VariantBuild build = geometry_build(geometry, "gerstner");
        MeshRenderSettings settings = small_settings(64);
        settings.overrides = {{"tess_scale", {1e4}}, {"tess_max", {3}}};
        const MeshRender all = render_mesh_variant(test::shared_runner(), build, scene, settings);
        settings.cull_back_faces = true;
        const MeshRender front = render_mesh_variant(test::shared_runner(), build, scene, settings);
        require_drawn(all);
        require_drawn(front);
        std::printf("%s: front-facing (counter-clockwise) coverage %llu of %llu pixels\n", geometry,
                    static_cast<unsigned long long>(front.covered),
                    static_cast<unsigned long long>(all.covered));
        CHECK(all.covered > 0u);
        // The water's upper side is front-facing under VK_FRONT_FACE_COUNTER_CLOCKWISE, as
        // variant.json's geometry says: all but the back of a crest folding over (none here).
        CHECK(front.covered == all.covered);
        CHECK(covered_pixels(front.gpu[1]) == front.covered);
    }
}

TEST_CASE("a_grid_out_of_range_or_a_screen_pass_variant_is_refused_before_drawing",
          "[render][mesh]") {
    const SyntheticScene scene = make_synthetic_scene(16, 16);
    const VariantBuild mesh = geometry_build("mesh", "sum_of_sines");
    MeshRenderSettings settings = small_settings(16);
    settings.grid.ring_cells = 15;
    MeshRender r = render_mesh_variant(test::shared_runner(), mesh, scene, settings);
    CHECK(r.error.find("ring_cells") != std::string::npos);
    settings.grid = {0.01, 512, 16}; // millions of vertices
    r = render_mesh_variant(test::shared_runner(), mesh, scene, settings);
    CHECK(r.error.find("vertices") != std::string::npos);
    const VariantBuild screen = build_variant(default_variant());
    r = render_mesh_variant(test::shared_runner(), screen, scene, small_settings(16));
    CHECK(r.error.find("screen-pass variant has no mesh") != std::string::npos);
}

TEST_CASE("runner_refuses_patches_without_tessellation_stages_and_stages_without_patches",
          "[render][mesh][tessellation]") {
    const VariantBuild build = geometry_build("tessellated", "sum_of_sines");
    const SyntheticScene scene = make_synthetic_scene(16, 16);
    const WaterGrid grid = water_grid({1.0, 16, 1}, 0.0, 0.0, GridTopology::Patches);
    RenderJob job = mesh_render_job(build.languages[0], scene, grid_mesh(grid),
                                    mesh_values(scene, grid, 16, 16), 16, 16, 0);
    {
        RenderJob flat = job; // patches through vertex and fragment stages alone
        flat.tess_control_spirv.clear();
        flat.tess_evaluation_spirv.clear();
        const RenderResult r = test::shared_runner().render(flat);
        CHECK_FALSE(r.ok);
        CHECK(r.error.find("patches of 4 control points need tessellation stages") !=
              std::string::npos);
    }
    {
        RenderJob triangles = job; // tessellation stages fed triangles
        triangles.mesh.patch_control_points = 0;
        triangles.mesh.indices = {0, 1, 2};
        const RenderResult r = test::shared_runner().render(triangles);
        CHECK_FALSE(r.ok);
        CHECK(r.error.find("tessellation stages need patches") != std::string::npos);
    }
    {
        RenderJob half = job; // a control stage without its evaluation stage
        half.tess_evaluation_spirv.clear();
        const RenderResult r = test::shared_runner().render(half);
        CHECK_FALSE(r.ok);
        CHECK(r.error.find("tess_evaluation SPIR-V is empty or not SPIR-V") != std::string::npos);
    }
    {
        RenderJob ragged = job; // not whole patches of 4
        ragged.mesh.indices.push_back(0);
        const RenderResult r = test::shared_runner().render(ragged);
        CHECK_FALSE(r.ok);
        CHECK(r.error.find("not whole patches of 4") != std::string::npos);
    }
    {
        RenderJob past = job; // an index past the vertices
        past.mesh.indices.back() = grid.vertex_count();
        const RenderResult r = test::shared_runner().render(past);
        CHECK_FALSE(r.ok);
        CHECK(r.error.find("is past its") != std::string::npos);
    }
    CHECK(test::shared_runner().render(job).ok);
}

TEST_CASE("vertex_emitter_reports_a_missing_position_output", "[waves][mesh]") {
    Graph g;
    Expr p = varying(g, "grid_xz", Type::Vec2);
    g.set_output("world", vec3(p, constant(g, 1.0)).id());
    Diagnostics ds;
    emit_vertex(g, Language::Glsl, "mesh", "v.vert.glsl", "test", ds);
    REQUIRE(has_errors(ds));
    CHECK(ds.front().message.find("position") != std::string::npos);
}
