// The parameter pass reaches every graph of a water shader: a material's value and range, and a
// scene's fixed value, land in the vertex and tessellation stages of a mesh geometry as in its
// fragment, and all stages then share one block. Before, a material setting a wave parameter
// could not build a mesh or tessellated variant ("declared by waves.gerstner at ... and by
// waves.gerstner at ... with different definitions": the fragment's declaration carried the
// material's value, the vertex stage's the node's default).
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/plan/material.h"
#include "watergen/plan/shader_fold.h"

using namespace watergen;

namespace {

std::string messages(const Diagnostics& ds) {
    std::string s;
    for (const Diagnostic& d : ds)
        s += format_diagnostic(d) + "\n";
    return s;
}

// examples/materials/mesh.json's axes with one geometry and Gerstner waves, and the steepness
// and its range set by the material.
Material steep_material(const std::string& geometry) {
    Diagnostics ds;
    auto m = MaterialBuilder("steep")
                 .preset("tropical_ocean")
                 .offer("fresnel", {"schlick"})
                 .offer("specular", {"blinn_phong"})
                 .offer("reflection", {"sky_cubemap"})
                 .offer("normals", {"analytic"})
                 .offer("waves", {"gerstner"})
                 .offer("shore", {"soft"})
                 .offer("geometry", {geometry})
                 .parameter("gerstner_steepness", {0.3})
                 .range("gerstner_steepness", 0.1, 0.5)
                 .build(ds);
    INFO(messages(ds));
    REQUIRE(m);
    return *m;
}

// The material's one variant (every axis offers one choice).
Variant only_variant(const Material& m) {
    std::vector<Variant> all;
    enumerate(m.space, [&](const Variant& v) { all.push_back(v); });
    REQUIRE(all.size() == 1);
    return all.front();
}

std::vector<const Graph*> all_graphs(const WaterShader& s) {
    std::vector<const Graph*> graphs = {&s.fragment};
    if (s.mesh)
        for (const Graph* g : std::as_const(*s.mesh).graphs())
            graphs.push_back(g);
    return graphs;
}

} // namespace

TEST_CASE("a_material_value_reaches_every_stage_of_a_mesh_geometry", "[pipeline][parameters]") {
    for (const std::string geometry : {"mesh", "tessellated"}) {
        INFO("geometry=" << geometry);
        const Material m = steep_material(geometry);
        WaterShader shader = m.compose(only_variant(m));
        REQUIRE(shader.mesh);
        size_t declaring = 0;
        for (const Graph* g : all_graphs(shader))
            if (const Parameter* p = g->find_parameter("gerstner_steepness")) {
                ++declaring;
                CHECK(p->default_value == std::vector<double>{0.3});
                CHECK(p->min == 0.1);
                CHECK(p->max == 0.5);
            }
        // The fragment (normals) and the stage that displaces the grid.
        CHECK(declaring >= 2);

        const VariantBuild b = build_shader(std::move(shader));
        INFO(messages(b.diagnostics));
        REQUIRE(b.ok());
        // Every stage of both languages that reads the steepness declares the material's value.
        size_t stages = 0;
        for (const LanguageBuild& lang : b.languages)
            for (const StageBuild* stage : lang.stages())
                for (const Parameter& p : stage->source.interface.parameters)
                    if (p.name == "gerstner_steepness") {
                        ++stages;
                        CHECK(p.default_value == std::vector<double>{0.3});
                        CHECK(p.min == 0.1);
                        CHECK(p.max == 0.5);
                    }
        CHECK(stages >= 4);
    }
}

TEST_CASE("a_scene_fixed_value_is_folded_into_every_stage", "[pipeline][parameters]") {
    for (const std::string geometry : {"mesh", "tessellated"}) {
        INFO("geometry=" << geometry);
        const Material m = steep_material(geometry);
        WaterShader shader = m.compose(only_variant(m));
        FoldFacts facts;
        facts.fixed["gerstner_steepness"] = {{0.25}, facts.add_fact("steepness = 0.25", "")};
        const FoldReport report = fold_water_shader(shader, facts);
        for (const Graph* g : all_graphs(shader))
            CHECK(g->find_parameter("gerstner_steepness") == nullptr);
        CHECK(report.folded_parameters.at("gerstner_steepness") == std::vector<double>{0.25});
        bool removed = false;
        for (const RemovedInput& r : report.removed_parameters)
            removed = removed || r.name == "gerstner_steepness";
        CHECK(removed);
        const VariantBuild b = build_shader(std::move(shader));
        INFO(messages(b.diagnostics));
        CHECK(b.ok());
    }
}
