// The mesh path: sum of sines and Gerstner displacing a 64x64 grid in a vertex stage, drawn
// indexed by the runner, GLSL path against HLSL path.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "shared_runner.h"
#include "watergen/eval/draw/mesh_render.h"
#include "watergen/ir/dsl.h"
#include "watergen/ir/vertex_emitter.h"

using namespace watergen;

TEST_CASE("mesh_path_renders_both_wave_models_identically_from_glsl_and_hlsl",
          "[render][waves][mesh]") {
    const MeshRenderSettings settings; // 128x128, 64x64 grid
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    for (const char* model : {"sum_of_sines", "gerstner"}) {
        INFO(model);
        const MeshBuild build = build_mesh(model);
        for (const auto& d : build.diagnostics)
            UNSCOPED_INFO(format_diagnostic(d));
        REQUIRE(build.ok());
        // The wave math is emitted once per language into the vertex stage only.
        for (const auto& lang : build.languages) {
            CHECK(lang.vertex.source.source.find("sin(") != std::string::npos);
            CHECK(lang.fragment.source.source.find("sin(") == std::string::npos);
        }
        const MeshRender r = render_mesh(test::shared_runner(), build, scene, settings);
        INFO(r.error);
        REQUIRE(r.ok());
        for (const auto& m : r.validation_messages)
            UNSCOPED_INFO(m);
        CHECK(r.validation_messages.empty());
        std::printf("mesh %-13s glsl-hlsl %.3g  first draw %.0f ms\n", model,
                    r.glsl_vs_hlsl.max_abs, r.gpu[0].first_draw_ms);
        // Same IR, same spirv-opt, same rasteriser: measured bit-identical.
        CHECK(r.glsl_vs_hlsl.max_abs <= 1e-6);
        CHECK(r.glsl_vs_hlsl.nan_inf_pixels == 0);
        CHECK(r.glsl_vs_hlsl.reference_nan_inf_pixels == 0);
        CHECK_FALSE(is_degenerate(r.gpu_image[0]));
        // The grid covers the lower part of the view; the fragment writes alpha 1, the clear 0.
        size_t covered = 0;
        for (size_t p = 0; p < size_t(settings.width) * settings.height; ++p)
            covered += r.gpu_image[0].rgba[p * 4 + 3] == 1.0f;
        CHECK(covered > size_t(settings.width) * settings.height / 3);
        if (const char* dir = std::getenv("WATERGEN_TEST_PNG_DIR")) {
            std::string error;
            write_png(std::string(dir) + "/mesh-" + model + ".png", settings.width, settings.height,
                      tone_map_to_srgb8(r.gpu_image[0]), &error);
        }
    }
}

TEST_CASE("grid_is_indexed_back_to_front", "[waves][mesh]") {
    const MeshData grid = make_grid(4, -1, 1, 0, 3);
    REQUIRE(grid.vertices.size() == 16u * 2u);
    REQUIRE(grid.indices.size() == 9u * 6u);
    // First triangle in the farthest row (largest z), last in the nearest.
    CHECK(grid.vertices[grid.indices.front() * 2 + 1] >= 2.0f);
    CHECK(grid.vertices[grid.indices.back() * 2 + 1] <= 1.0f);
}

TEST_CASE("runner_rejects_a_mesh_whose_indices_run_past_its_vertices", "[render][mesh]") {
    const MeshBuild build = build_mesh("sum_of_sines");
    REQUIRE(build.ok());
    RenderJob job;
    job.vertex_spirv = build.languages[0].vertex.toolchain.spirv_optimized;
    job.fragment_spirv = build.languages[0].fragment.toolchain.spirv_optimized;
    job.vertex_reflection = build.languages[0].vertex.toolchain.reflection;
    job.fragment_reflection = build.languages[0].fragment.toolchain.reflection;
    job.width = job.height = 16;
    job.timed_draws = 0;
    const ShaderInterface& in = build.languages[0].vertex.source.interface;
    job.uniforms = pack_uniforms(in.uniforms, in.parameters);
    job.mesh = make_grid(2, 0, 1, 0, 1);
    job.mesh.indices.back() = 4;
    const RenderResult r = test::shared_runner().render(job);
    CHECK_FALSE(r.ok);
    CHECK(r.error.find("mesh index 4 is past its 4 vertices") != std::string::npos);
}

TEST_CASE("vertex_emitter_reports_a_missing_position_output", "[waves][mesh]") {
    Graph g;
    Expr p = varying(g, "grid_xz", Type::Vec2);
    g.set_output("normal", vec3(p, constant(g, 1.0)).id());
    Diagnostics ds;
    emit_vertex(g, Language::Glsl, "mesh", "v.vert.glsl", "test", ds);
    REQUIRE(has_errors(ds));
    CHECK(ds.front().message.find("position") != std::string::npos);
}
