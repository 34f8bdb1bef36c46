// The tessellated mesh path drawn on lavapipe (issue 28): quad patches through vertex, control,
// evaluation and fragment stages in both languages, GLSL path against HLSL path; at factor 1
// against the mesh path over the same grid points; tess_max past 64 (or below 1) drawing what
// the clamp gives.
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>

#include "shared_runner.h"
#include "watergen/eval/draw/tessellated_mesh_render.h"

using namespace watergen;

namespace {

size_t covered_pixels(const ImageRGBA32F& image) {
    size_t covered = 0;
    for (size_t p = 0; p < size_t(image.width) * image.height; ++p)
        covered += image.rgba[p * 4 + 3] == 1.0f;
    return covered;
}

// Pixels whose RGBA differ at all.
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

TEST_CASE("tessellated_patches_split_as_the_skeletons_say", "[waves][mesh][tessellation]") {
    const MeshData patches = make_patches(3, -1, 1, 0, 2);
    REQUIRE(patches.vertices.size() == 9u * 2u);
    CHECK(patches.patch_control_points == 4u);
    REQUIRE(patches.indices.size() == 4u * 4u);
    // First patch in the far row: corners (0, 1), (1, 1), (0, 2), (1, 2) of the grid.
    const std::vector<uint32_t> first(patches.indices.begin(), patches.indices.begin() + 4);
    CHECK(first == std::vector<uint32_t>{3, 4, 6, 7});
    // Corner order (u, v) = (0, 0), (1, 0), (0, 1), (1, 1): x grows with u, z with v.
    auto x = [&](uint32_t i) { return patches.vertices[i * 2]; };
    auto z = [&](uint32_t i) { return patches.vertices[i * 2 + 1]; };
    CHECK(x(first[1]) > x(first[0]));
    CHECK(z(first[2]) > z(first[0]));
    CHECK(x(first[3]) == x(first[1]));
    CHECK(z(first[3]) == z(first[2]));
}

TEST_CASE("tessellated_mesh_renders_identically_from_glsl_and_hlsl",
          "[render][waves][mesh][tessellation]") {
    REQUIRE(test::shared_runner().device_info().tessellation_shader);
    CHECK(test::shared_runner().device_info().max_tessellation_level >= 64u);
    MeshRenderSettings settings; // 128x128
    settings.grid = 16;          // 15 x 15 patches of about 1.9 x 2.3 m
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    for (const char* model : {"sum_of_sines", "gerstner"}) {
        INFO(model);
        const TessellatedMeshBuild build = build_tessellated_mesh(model);
        for (const auto& d : build.diagnostics)
            UNSCOPED_INFO(format_diagnostic(d));
        REQUIRE(build.ok());
        const MeshRender r = render_tessellated_mesh(test::shared_runner(), build, scene, settings);
        require_drawn(r);
        const size_t covered = covered_pixels(r.gpu_image[0]);
        std::printf("tessellated %-13s glsl-hlsl max abs %.3g, %zu of %u pixels covered, first "
                    "draw %.0f ms\n",
                    model, r.glsl_vs_hlsl.max_abs, covered, settings.width * settings.height,
                    r.gpu[0].first_draw_ms);
        // Same graphs, same domain and winding, same rasteriser: bit-identical.
        CHECK(r.glsl_vs_hlsl.max_abs == 0.0);
        CHECK(differing_pixels(r.gpu_image[0], r.gpu_image[1]) == 0u);
        CHECK(r.glsl_vs_hlsl.nan_inf_pixels == 0);
        CHECK_FALSE(is_degenerate(r.gpu_image[0]));
        CHECK(covered > size_t(settings.width) * settings.height / 3);
        if (const char* dir = std::getenv("WATERGEN_TEST_PNG_DIR")) {
            std::string error;
            write_png(std::string(dir) + "/mesh-tessellated-" + model + ".png", settings.width,
                      settings.height, tone_map_to_srgb8(r.gpu_image[0]), &error);
        }
    }
}

TEST_CASE("tessellated_mesh_at_factor_1_matches_the_mesh_path_over_the_same_points",
          "[render][waves][mesh][tessellation]") {
    const MeshRenderSettings settings; // 128x128, 64 x 64 points: 63 x 63 cells either way
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    const TessellatedMeshBuild tess = build_tessellated_mesh("gerstner");
    const MeshBuild mesh = build_mesh("gerstner");
    REQUIRE(tess.ok());
    REQUIRE(mesh.ok());
    // tess_max 1: every factor 1, each patch one quad of two triangles over its corners.
    const MeshRender t =
        render_tessellated_mesh(test::shared_runner(), tess, scene, settings, {{"tess_max", {1}}});
    require_drawn(t);
    const MeshRender m = render_mesh(test::shared_runner(), mesh, scene, settings);
    require_drawn(m);
    const ImageErrorStats e = compare_images(t.gpu_image[0], m.gpu_image[0]);
    const size_t differing = differing_pixels(t.gpu_image[0], m.gpu_image[0]);
    std::printf("tessellated at factor 1 vs mesh (gerstner, 64 points): max abs %.3g, rmse %.3g, "
                "%zu differing pixels, covered %zu vs %zu\n",
                e.max_abs, e.rmse, differing, covered_pixels(t.gpu_image[0]),
                covered_pixels(m.gpu_image[0]));
    CHECK(t.glsl_vs_hlsl.max_abs == 0.0);
    CHECK(e.nan_inf_pixels == 0);
    // The same triangles (the tessellator splits each quad along the diagonal make_grid uses,
    // else the interpolated normals would differ by far more): the same pixels covered, values
    // apart by float rounding alone (measured 4.2e-7 at most, on 343 of 16384 pixels).
    CHECK(covered_pixels(t.gpu_image[0]) == covered_pixels(m.gpu_image[0]));
    CHECK(e.max_abs <= 1e-6);
}

TEST_CASE("tess_max_out_of_range_draws_what_the_shader_clamp_gives",
          "[render][waves][mesh][tessellation]") {
    MeshRenderSettings settings;
    settings.width = settings.height = 64;
    settings.grid = 4; // 9 patches, so factor 64 stays a small draw
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    const TessellatedMeshBuild build = build_tessellated_mesh("gerstner");
    REQUIRE(build.ok());
    auto draw = [&](double tess_max) {
        const MeshRender r =
            render_tessellated_mesh(test::shared_runner(), build, scene, settings,
                                    {{"tess_scale", {1e4}}, {"tess_max", {tess_max}}});
        require_drawn(r);
        CHECK(r.glsl_vs_hlsl.max_abs == 0.0);
        return r.gpu_image[0];
    };
    // 100 is refused by no one before the shader: it draws exactly what 64 draws.
    const ImageRGBA32F at_64 = draw(64), at_100 = draw(100);
    CHECK(differing_pixels(at_64, at_100) == 0u);
    // 0 draws what 1 draws (never a culled patch).
    const ImageRGBA32F at_1 = draw(1), at_0 = draw(0);
    CHECK(differing_pixels(at_1, at_0) == 0u);
    CHECK(covered_pixels(at_0) > 0u);
    // And the factor matters: 64 and 1 differ.
    const size_t differing = differing_pixels(at_64, at_1);
    std::printf("tess_max 64 vs 1 over 3 x 3 patches: %zu of %u pixels differ\n", differing,
                settings.width * settings.height);
    CHECK(differing > 0u);
}

TEST_CASE("tessellated_triangles_face_the_eye_counter_clockwise_on_lavapipe",
          "[render][waves][mesh][tessellation]") {
    MeshRenderSettings settings;
    settings.width = settings.height = 64;
    settings.grid = 16;
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    const TessellatedMeshBuild tess = build_tessellated_mesh("gerstner");
    const MeshBuild mesh = build_mesh("gerstner");
    REQUIRE(tess.ok());
    REQUIRE(mesh.ok());
    // Factor 3 everywhere: the tessellator's own triangles, not one quad per patch.
    const std::map<std::string, std::vector<double>> factor_3 = {{"tess_scale", {1e4}},
                                                                 {"tess_max", {3}}};
    const MeshRender t_all =
        render_tessellated_mesh(test::shared_runner(), tess, scene, settings, factor_3);
    const MeshRender m_all = render_mesh(test::shared_runner(), mesh, scene, settings);
    settings.cull_back_faces = true;
    const MeshRender t_culled =
        render_tessellated_mesh(test::shared_runner(), tess, scene, settings, factor_3);
    const MeshRender m_culled = render_mesh(test::shared_runner(), mesh, scene, settings);
    for (const MeshRender* r : {&t_all, &m_all, &t_culled, &m_culled})
        require_drawn(*r);
    const size_t t_front = covered_pixels(t_culled.gpu_image[0]);
    const size_t m_front = covered_pixels(m_culled.gpu_image[0]);
    std::printf("front-facing (counter-clockwise) coverage: tessellated %zu of %zu, mesh %zu of "
                "%zu\n",
                t_front, covered_pixels(t_all.gpu_image[0]), m_front,
                covered_pixels(m_all.gpu_image[0]));
    CHECK(covered_pixels(t_all.gpu_image[0]) > 0u);
    // Quads, clockwise in Vulkan's upper-left (u, v) domain, with u along +x and v along +z
    // (up the screen, so v is mirrored): every tessellated triangle is counter-clockwise in the
    // framebuffer, the water's upper side front-facing under VK_FRONT_FACE_COUNTER_CLOCKWISE
    // (measured 3172 of 3172 pixels), in both languages alike.
    CHECK(t_front == covered_pixels(t_all.gpu_image[0]));
    CHECK(covered_pixels(t_culled.gpu_image[1]) == t_front);
    // make_grid's triangles (a, c, b) wind the other way: back-facing but where a Gerstner crest
    // folds over (measured 22 of 3174 pixels front-facing). Nothing here culls, so the images
    // agree; an engine culling either path must know this.
    CHECK(m_front < covered_pixels(m_all.gpu_image[0]) / 50);
}

TEST_CASE("runner_refuses_patches_without_tessellation_stages_and_stages_without_patches",
          "[render][mesh][tessellation]") {
    const TessellatedMeshBuild build = build_tessellated_mesh("sum_of_sines");
    REQUIRE(build.ok());
    RenderJob job =
        tessellated_mesh_job(build.languages[0], make_patches(2, 0, 1, 0, 1), 16, 16, {}, 0);
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
        RenderJob ragged = job; // 5 indices: not whole patches of 4
        ragged.mesh.indices.push_back(0);
        const RenderResult r = test::shared_runner().render(ragged);
        CHECK_FALSE(r.ok);
        CHECK(r.error.find("5 indices, not whole patches of 4") != std::string::npos);
    }
    CHECK(test::shared_runner().render(job).ok);
}

TEST_CASE("tessellated_mesh_at_factor_3_matches_the_mesh_path_at_the_same_spacing",
          "[render][waves][mesh][tessellation]") {
    const MeshRenderSettings settings; // 128x128, the mesh over 64 x 64 points
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    const TessellatedMeshBuild tess = build_tessellated_mesh("gerstner");
    const MeshBuild mesh = build_mesh("gerstner");
    REQUIRE(tess.ok());
    REQUIRE(mesh.ok());
    // 22 x 22 points, 21 patches per side cut in 3 (factor 3 on every edge and inside): 63
    // segments per side at the mesh's spacing, the tessellator's triangles in place of
    // make_grid's.
    MeshRenderSettings coarse = settings;
    coarse.grid = 22;
    const MeshRender t = render_tessellated_mesh(test::shared_runner(), tess, scene, coarse,
                                                 {{"tess_scale", {1e4}}, {"tess_max", {3}}});
    require_drawn(t);
    const MeshRender m = render_mesh(test::shared_runner(), mesh, scene, settings);
    require_drawn(m);
    const ImageErrorStats e = compare_images(t.gpu_image[0], m.gpu_image[0]);
    std::printf("tessellated at factor 3 over 22 points vs mesh over 64 (gerstner): max abs %.3g, "
                "rmse %.3g, CIEDE2000 mean %.3g p99 %.3g\n",
                e.max_abs, e.rmse, e.ciede2000_mean, e.ciede2000_p99);
    CHECK(t.glsl_vs_hlsl.max_abs == 0.0);
    // The same surface: the same pixels covered; other diagonals inside the patches move the
    // interpolated normals a little (measured max abs 0.176, rmse 0.0020, CIEDE2000 mean 0.026,
    // p99 0.31: below a just-noticeable difference).
    CHECK(covered_pixels(t.gpu_image[0]) == covered_pixels(m.gpu_image[0]));
    CHECK(e.rmse < 0.005);
    CHECK(e.ciede2000_p99 < 1.0);
}
