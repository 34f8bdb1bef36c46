// A mesh variant of a build (examples/materials/mesh.json) drawn as an engine draws it, through
// the runtime library only (ShaderBuild, the manifest's geometry, water_grid(), UniformWriter,
// VariantPipeline with the grid's vertex input, HeadlessDevice::draw over the grid), gives the
// image the test runner draws of the same variant built in-process over the same grid: max abs
// 0, for the mesh and the tessellated geometry. What examples/engine_consumer does.
#include <catch2/catch.hpp>

#include <cmath>

#include "build_test_support.h"
#include "engine_draw_support.h"
#include "shared_runner.h"
#include "watergen/eval/draw/mesh_render.h"
#include "watergen/eval/draw/variant_render.h"
#include "watergen/headless/headless_device.h"
#include "watergen/pipeline/build/build_output.h"
#include "watergen/plan/material.h"
#include "watergen/runtime/uniform_writer.h"
#include "watergen/runtime/water_grid.h"
#include "watergen/water/presets.h"

using namespace watergen;
using namespace watergen::test;

namespace {

constexpr uint32_t kSize = 96;

const std::filesystem::path& mesh_build() {
    static TempDir dir("engine-mesh");
    static bool built = false;
    if (!built) {
        Diagnostics ds;
        auto material = load_material(source_dir() + "/examples/materials/mesh.json", ds);
        REQUIRE(material);
        BuildRequest request;
        request.material = *material;
        request.out = dir.path / "out";
        REQUIRE(build_material(request).ok());
        built = true;
    }
    static const std::filesystem::path out = dir.path / "out";
    return out;
}

} // namespace

TEST_CASE("a mesh variant drawn through the runtime library matches the test runner exactly") {
    std::string error;
    const auto b = ShaderBuild::open(mesh_build(), &error);
    INFO(error);
    REQUIRE(b);
    const Preset* preset = find_preset("tropical_ocean");
    const SyntheticScene scene = preset_scene(kSize, kSize, preset);
    const SceneCamera cam = scene_camera(scene.view, kSize, kSize);
    for (const char* geometry : {"mesh", "tessellated"}) {
        INFO(geometry);
        const Selection s =
            b->select("", {{"geometry", geometry}, {"waves", "gerstner"}, {"foam", "shore"}});
        INFO(s.error);
        REQUIRE(s.ok());
        const BuildVariant& v = *s.variant;
        // The manifest says how to draw it.
        REQUIRE(v.geometry);
        CHECK(v.geometry->name == geometry);
        CHECK(v.geometry->attribute_sizes() == std::vector<uint32_t>{2, 3});
        CHECK(v.geometry->vertex_stride == 20u);
        CHECK(v.geometry->stages.size() == (v.geometry->tessellated() ? 4u : 2u));
        const WaterGrid grid =
            water_grid({1.0, 16, 6}, cam.eye[0], cam.eye[2],
                       v.geometry->tessellated() ? GridTopology::Patches : GridTopology::Triangles);
        const std::map<std::string, std::vector<double>> values =
            mesh_values(scene, grid, kSize, kSize);

        // The runner: the same variant built in-process, over the same grid.
        Variant variant = default_variant();
        for (const auto& [axis, choice] : v.choices)
            REQUIRE_FALSE(set_choice(variant, axis, choice));
        const VariantBuild reference = build_variant(variant, preset);
        REQUIRE(reference.ok());
        RenderJob job = mesh_render_job(reference.languages[0], scene, grid_mesh(grid), values,
                                        kSize, kSize, 0);
        job.background.clear(); // the engine draws into its cleared target too
        const RenderResult expected = test::shared_runner().render(job);
        INFO(expected.error);
        REQUIRE(expected.ok);

        // The engine: the build's files, the library's packing, pipeline and draw.
        const auto spirv = [&](ShaderStage stage) {
            auto words = b->spirv(v, "glsl", stage, &error);
            INFO(error);
            REQUIRE(words);
            return *words;
        };
        const auto reflection = [&](ShaderStage stage) {
            auto r = b->reflection(v, "glsl", stage, &error);
            INFO(error);
            REQUIRE(r);
            return *r;
        };
        const std::vector<uint32_t> vs = spirv(ShaderStage::Vertex),
                                    fs = spirv(ShaderStage::Fragment);
        const Reflection vr = reflection(ShaderStage::Vertex),
                         fr = reflection(ShaderStage::Fragment);
        CHECK(vr.inputs.size() == 2u); // the vertex inputs, reflected
        UniformWriter writer(v);
        for (const auto& [name, value] : values)
            if (writer.has(name))
                REQUIRE(writer.set(name, std::vector<float>(value.begin(), value.end())).ok);
        const auto bytes = writer.pack(fr, &error);
        REQUIRE(bytes);
        CHECK(*bytes == job.uniforms);
        VariantPipelineDesc desc{&vs, &fs, &vr, &fr, engine_gpu().render_pass(), 0, {}, {}};
        std::vector<uint32_t> tcs, tes;
        Reflection tcr, ter;
        if (v.geometry->tessellated()) {
            tcs = spirv(ShaderStage::TessControl);
            tes = spirv(ShaderStage::TessEvaluation);
            tcr = reflection(ShaderStage::TessControl);
            ter = reflection(ShaderStage::TessEvaluation);
            desc.tess_control_spirv = &tcs;
            desc.tess_evaluation_spirv = &tes;
            desc.tess_control_reflection = &tcr;
            desc.tess_evaluation_reflection = &ter;
        }
        PipelineGeometry geo;
        geo.attribute_sizes = v.geometry->attribute_sizes();
        geo.patch_control_points = v.geometry->patch_control_points;
        auto pipeline = VariantPipeline::create(engine_gpu().device(), desc, geo, &error);
        INFO(error);
        REQUIRE(pipeline);
        HeadlessDraw draw;
        draw.width = draw.height = kSize;
        draw.uniforms[v.block_name] = *bytes;
        draw.textures = scene.textures;
        draw.vertices = &grid.vertices;
        draw.indices = &grid.indices;
        draw.attribute_sizes = geo.attribute_sizes;
        draw.patch_control_points = grid.patch_control_points;
        const std::vector<float> got = engine_gpu().draw(*pipeline, draw, &error);
        INFO(error);
        REQUIRE(got.size() == expected.rgba.size());
        const double diff = max_abs_difference(got, expected.rgba);
        WARN(geometry << ": runtime library vs test runner, " << kSize << "x" << kSize
                      << ", max abs " << diff);
        CHECK(diff == 0.0);
        size_t covered = 0;
        for (size_t p = 0; p < got.size() / 4; ++p)
            covered += got[p * 4 + 3] != 0.0f;
        CHECK(covered > size_t(kSize) * kSize / 2);
    }
    CHECK(engine_gpu().validation_messages().empty());
}
