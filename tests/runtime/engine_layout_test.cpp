// One layout for a whole build: the pipelines of a build made with the frequency_sets binding
// map all take the one BindingLayout the runtime makes from the manifest's "bindings" (not one
// re-derived per variant), draw exactly what a pipeline of its own layout draws, and a stage
// whose descriptors are off the map is refused naming the descriptor.
#include <catch2/catch.hpp>

#include "build_test_support.h"
#include "engine_draw_support.h"
#include "watergen/pipeline/build/build_output.h"
#include "watergen/plan/material.h"
#include "watergen/runtime/binding_layout.h"
#include "watergen/runtime/variant_pipeline.h"
#include "watergen/water/binding_profiles.h"

using namespace watergen;
using namespace watergen::test;

namespace {

const ShaderBuild& frequency_sets_build() {
    static TempDir dir("engine-frequency-sets");
    static const ShaderBuild build = [] {
        Diagnostics ds;
        auto material = load_material(source_dir() + "/examples/materials/default.json", ds);
        REQUIRE(material);
        BuildRequest request;
        request.material = *material;
        request.out = dir.path / "out";
        request.options.bindings = binding_profile("frequency_sets");
        REQUIRE(build_material(request).ok());
        std::string error;
        auto b = ShaderBuild::open(dir.path / "out", &error);
        INFO(error);
        REQUIRE(b);
        return *b;
    }();
    return build;
}

struct Stages {
    std::vector<uint32_t> vs, fs;
    Reflection vr, fr;
};

Stages stages(const ShaderBuild& b, const BuildVariant& v, const std::string& lang) {
    std::string error;
    auto vs = b.spirv(v, lang, ShaderStage::Vertex, &error);
    auto fs = b.spirv(v, lang, ShaderStage::Fragment, &error);
    auto vr = b.reflection(v, lang, ShaderStage::Vertex, &error);
    auto fr = b.reflection(v, lang, ShaderStage::Fragment, &error);
    INFO(error);
    REQUIRE((vs && fs && vr && fr));
    return {*vs, *fs, *vr, *fr};
}

} // namespace

TEST_CASE("every pipeline of a build takes the binding map's one layout") {
    const ShaderBuild& b = frequency_sets_build();
    REQUIRE(b.bindings().map == "frequency_sets");
    REQUIRE(b.bindings().slots.size() == 14);
    const MapSlot* params = b.bindings().find("WaterParams");
    REQUIRE(params);
    CHECK(params->set == 2);
    CHECK(params->kind == DescriptorKind::UniformBuffer);
    std::string error;
    auto layout = BindingLayout::create(engine_gpu().device(), b.bindings(), &error);
    INFO(error);
    REQUIRE(layout);
    REQUIRE(layout->set_layouts().size() == 3); // set 1 empty: the engine's per-object data

    // A spread of the build's variants through both language paths: one layout for all.
    size_t made = 0;
    for (size_t i = 0; i < b.variants().size(); i += 24)
        for (const char* lang : {"glsl", "hlsl"}) {
            const BuildVariant& v = b.variants()[i];
            INFO(v.key << " " << lang);
            const Stages s = stages(b, v, lang);
            VariantPipelineDesc desc{&s.vs, &s.fs, &s.vr, &s.fr, engine_gpu().render_pass(), 0, {}};
            desc.layout = &*layout;
            auto p = VariantPipeline::create(engine_gpu().device(), desc, &error);
            INFO(error);
            REQUIRE(p);
            CHECK(p->layout() == layout->layout());
            CHECK(p->set_layouts() == layout->set_layouts());
            ++made;
        }
    CHECK(made == 12);

    // The same image as the variant's pipeline with a layout of its own.
    const Selection sel = b.select("",
                                   {{"reflection", "sky_cubemap"},
                                    {"waves", "gerstner"},
                                    {"foam", "shore"},
                                    {"precision", "full"}},
                                   Fallback::NearestKept);
    INFO(sel.error);
    REQUIRE(sel.ok());
    const SyntheticScene scene = make_synthetic_scene(64, 64);
    for (const char* lang : {"glsl", "hlsl"}) {
        const EngineDraw own =
            engine_draw(b, *sel.variant, lang, scene.uniforms, scene.textures, 64);
        const EngineDraw shared = engine_draw(b, *sel.variant, lang, scene.uniforms, scene.textures,
                                              64, VK_NULL_HANDLE, &*layout);
        CHECK(max_abs_difference(shared.rgba, own.rgba) == 0.0);
    }

    // A stage off the map: refused, naming the descriptor and the map's slot.
    Stages off = stages(b, *sel.variant, "glsl");
    REQUIRE_FALSE(off.fr.bindings.empty());
    off.fr.bindings.front().binding += 7;
    VariantPipelineDesc desc{&off.vs, &off.fs, &off.vr, &off.fr, engine_gpu().render_pass(), 0, {}};
    desc.layout = &*layout;
    CHECK_FALSE(VariantPipeline::create(engine_gpu().device(), desc, &error));
    CHECK(error.find("fragment stage: ") == 0);
    CHECK(error.find("the binding map 'frequency_sets' has it as") != std::string::npos);

    // A map the layout cannot hold.
    BuildBindings past = b.bindings();
    past.slots.front().set = 4;
    CHECK_FALSE(BindingLayout::create(engine_gpu().device(), past, &error));
    CHECK(error.find("expected a set below 4") != std::string::npos);
}
