// The tessellated geometry's emission and validation (geometry=tessellated): four stages per
// language (patch vertex, tessellation control / hull, tessellation evaluation / domain, the
// water fragment) through glslang's GLSL and HLSL front ends, spirv-val, spirv-opt and
// reflection; all stages share one parameter block; both languages state the same domain,
// spacing and winding; the GL and Metal targets skip the patch stages with a note; factors
// stay in [1, 64] whatever tess_max holds. No device.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <set>
#include <utility>

#include "geometry_variant.h"
#include "watergen/ir/core/dsl.h"
#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/ir/emit/tessellation_emitter.h"
#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/runtime/host_values.h"
#include "watergen/runtime/reflection.h"
#include "watergen/water/tessellated_mesh.h"

using namespace watergen;
using watergen::test::geometry_variant;

namespace {

VariantBuild tessellated_build(const std::string& model) {
    return build_variant(geometry_variant("tessellated", model));
}

// The control stage of the tessellated geometry on its own.
Graph control_graph() {
    Graph g;
    build_tess_control(g);
    return g;
}

std::string messages(const Diagnostics& ds) {
    std::string s;
    for (const auto& d : ds)
        s += format_diagnostic(d) + "\n";
    return s;
}

const DescriptorBinding* find_block(const Reflection& r) {
    for (const auto& b : r.bindings)
        if (b.name == "WaterParams") return &b;
    return nullptr;
}

const UniformMember* find_member(const DescriptorBinding& b, const std::string& name) {
    for (const auto& m : b.members)
        if (m.name == name) return &m;
    return nullptr;
}

// (mode, first literal or 0) of each OpExecutionMode in a module.
std::set<std::pair<uint32_t, uint32_t>> execution_modes(const std::vector<uint32_t>& spirv) {
    constexpr uint32_t kOpExecutionMode = 16;
    std::set<std::pair<uint32_t, uint32_t>> modes;
    for (size_t i = 5; i < spirv.size();) {
        const uint32_t count = spirv[i] >> 16, op = spirv[i] & 0xffffu;
        if (count == 0) break;
        if (op == kOpExecutionMode && count >= 3)
            modes.insert({spirv[i + 2], count >= 4 ? spirv[i + 3] : 0});
        i += count;
    }
    return modes;
}

bool has_note(const Diagnostics& ds, const std::string& text) {
    return std::any_of(ds.begin(), ds.end(), [&](const Diagnostic& d) {
        return d.severity == Severity::Note && d.message.find(text) != std::string::npos;
    });
}

// The control graph's factors for one patch, evaluated on the CPU in float.
std::map<std::string, double> factors(const Graph& control,
                                      const std::map<std::string, std::vector<double>>& uniforms,
                                      const std::vector<std::vector<double>>& corners) {
    EvalInputs in;
    in.uniforms = uniforms;
    in.lanes = 1;
    in.threads = 1;
    // The corners are world (x, z); the vertex buffer holds them in the shader's frame, whose
    // centre follows the eye (host_values.h).
    const std::vector<double>& eye = uniforms.at("eye_position");
    const FrameCentre c = frame_centre_of(eye[0], eye[2]);
    for (size_t i = 0; i < 4; ++i)
        in.varyings["corner_" + std::to_string(i)] = {corners[i][0] - c.x, corners[i][1] - c.z};
    std::map<std::string, double> out;
    for (const char* name : {"outer_0", "outer_1", "outer_2", "outer_3", "inner_0", "inner_1"}) {
        const EvalResult r = evaluate(control, name, in, EvalPrecision::Float);
        INFO(r.error);
        REQUIRE(r.ok());
        out[name] = r.values.at(0);
    }
    return out;
}

} // namespace

TEST_CASE("tessellated_mesh_stages_compile_validate_and_reflect_in_both_languages",
          "[tessellation][mesh]") {
    for (const char* model : {"sum_of_sines", "gerstner"}) {
        INFO(model);
        const VariantBuild b = tessellated_build(model);
        INFO(messages(b.diagnostics));
        REQUIRE(b.ok());
        REQUIRE(b.shader.mesh);
        std::vector<const Graph*> graphs = b.shader.mesh->graphs();
        graphs.push_back(&b.shader.fragment);
        Diagnostics ignored;
        const std::vector<Parameter> shared = shared_block_parameters(graphs, ignored);
        const std::set<std::pair<uint32_t, uint32_t>> expected_modes = {
            {26, 4}, // OutputVertices 4
            {24, 0}, // Quads
            {3, 0},  // SpacingFractionalOdd
            {4, 0},  // VertexOrderCw
        };
        std::array<const DescriptorBinding*, 2> evaluation_blocks{};
        for (size_t l = 0; l < 2; ++l) {
            const LanguageBuild& lang = b.languages[l];
            REQUIRE(lang.tessellated());
            INFO(to_string(lang.language));
            const std::pair<const StageBuild*, ShaderStage> stages[] = {
                {&lang.vertex, ShaderStage::Vertex},
                {&lang.control, ShaderStage::TessControl},
                {&lang.evaluation, ShaderStage::TessEvaluation},
                {&lang.fragment, ShaderStage::Fragment}};
            for (const auto& [stage, kind] : stages) {
                INFO(stage->source.file_name);
                CHECK(stage->source.stage == kind);
                // Compiled by glslang, passed spirv-val before and after spirv-opt, reflected.
                CHECK(stage->toolchain.ok());
                CHECK_FALSE(stage->toolchain.spirv.empty());
                CHECK_FALSE(stage->toolchain.spirv_optimized.empty());
                CHECK(stage->toolchain.reflection.stage == kind);
                CHECK(stage->toolchain.reflection.entry_point == "main");
            }
            // The patch vertex stage: the grid's attributes in (the morph needs the level),
            // the morphed grid_xz out at location 0, the block (the morph reads the eye).
            const Reflection& vert = lang.vertex.toolchain.reflection;
            REQUIRE(vert.inputs.size() == 2);
            CHECK(vert.inputs[0].name == "grid_xz");
            CHECK(vert.inputs[0].location == 0);
            CHECK(vert.inputs[0].type == "vec2");
            CHECK(vert.inputs[1].name == "grid_lod");
            CHECK(vert.inputs[1].location == 1);
            CHECK(vert.inputs[1].type == "vec3");
            REQUIRE(vert.outputs.size() == 1);
            CHECK(vert.outputs[0].location == 0);
            CHECK(vert.outputs[0].type == "vec2");
            CHECK(find_block(vert));
            // Control: per-control-point arrays of grid_xz in and out, the block.
            const Reflection& tesc = lang.control.toolchain.reflection;
            REQUIRE(tesc.inputs.size() == 1);
            CHECK(tesc.inputs[0].location == 0);
            CHECK(tesc.inputs[0].type.rfind("vec2[", 0) == 0);
            REQUIRE(tesc.outputs.size() == 1);
            CHECK(tesc.outputs[0].type == "vec2[4]");
            const DescriptorBinding* control_block = find_block(tesc);
            REQUIRE(control_block);
            // Evaluation: the control points in; out, what the water fragment reads.
            const Reflection& tese = lang.evaluation.toolchain.reflection;
            REQUIRE(tese.inputs.size() == 1);
            CHECK(tese.inputs[0].location == 0);
            const auto fragment_inputs = mesh_fragment_inputs();
            REQUIRE(tese.outputs.size() == fragment_inputs.size());
            const char* types[] = {"vec3", "vec2", "vec4"};
            for (size_t o = 0; o < tese.outputs.size(); ++o) {
                CHECK(tese.outputs[o].name == fragment_inputs[o].first);
                CHECK(tese.outputs[o].location == o);
                CHECK(tese.outputs[o].type == types[o]);
            }
            const DescriptorBinding* block = find_block(tese);
            REQUIRE(block);
            evaluation_blocks[l] = block;
            CHECK(block->kind == DescriptorKind::UniformBuffer);
            for (const char* member : {"eye_position", "water_level", "time", "mesh_projection",
                                       "tess_scale", "tess_max"})
                CHECK(find_member(*block, member));
            // One uniform buffer for every stage: the same members at the same offsets.
            for (const StageBuild* other : {&lang.vertex, &lang.control, &lang.fragment}) {
                INFO(other->source.file_name);
                const DescriptorBinding* b2 = find_block(other->toolchain.reflection);
                REQUIRE(b2);
                CHECK(b2->set == block->set);
                CHECK(b2->binding == block->binding);
                CHECK(b2->block_size == block->block_size);
                REQUIRE(b2->members.size() == block->members.size());
                for (size_t m = 0; m < block->members.size(); ++m) {
                    CHECK(b2->members[m].name == block->members[m].name);
                    CHECK(b2->members[m].offset == block->members[m].offset);
                }
            }
            // Every parameter of the block but the loop counts (specialization constants).
            CHECK(block->members.size() ==
                  size_t(std::count_if(shared.begin(), shared.end(),
                                       [](const Parameter& p) { return !p.specialization; })));
            // Domain, spacing, winding and patch size, over the two patch stages.
            std::set<std::pair<uint32_t, uint32_t>> modes =
                execution_modes(lang.control.toolchain.spirv);
            const auto more = execution_modes(lang.evaluation.toolchain.spirv);
            modes.insert(more.begin(), more.end());
            CHECK(modes == expected_modes);
            // The displacement lives in the evaluation stage (the fragment evaluates the
            // slope per pixel), not before it.
            CHECK(lang.evaluation.source.source.find("sin(") != std::string::npos);
            for (const StageBuild* s : {&lang.vertex, &lang.control})
                CHECK(s->source.source.find("sin(") == std::string::npos);
        }
        // GLSL's block and HLSL's cbuffer agree.
        REQUIRE(evaluation_blocks[0]->members.size() == evaluation_blocks[1]->members.size());
        for (size_t m = 0; m < evaluation_blocks[0]->members.size(); ++m) {
            CHECK(evaluation_blocks[0]->members[m].name == evaluation_blocks[1]->members[m].name);
            CHECK(evaluation_blocks[0]->members[m].offset ==
                  evaluation_blocks[1]->members[m].offset);
        }
        // The HLSL hull names its patch-constant function; the GLSL stages state the domain.
        const std::string& hull = b.languages[1].control.source.source;
        CHECK(hull.find("[patchconstantfunc(\"mesh_patch_factors\")]") != std::string::npos);
        CHECK(hull.find("[partitioning(\"fractional_odd\")]") != std::string::npos);
        CHECK(b.languages[0].evaluation.source.source.find(
                  "layout(quads, fractional_odd_spacing, cw) in;") != std::string::npos);
    }
}

TEST_CASE("tessellation_stages_skip_the_gl_and_metal_targets_with_a_note", "[tessellation][mesh]") {
    const VariantBuild b = tessellated_build("gerstner");
    INFO(messages(b.diagnostics));
    REQUIRE(b.ok());
    for (const LanguageBuild& lang : b.languages) {
        INFO(to_string(lang.language));
        for (const StageBuild* s : {&lang.control, &lang.evaluation}) {
            INFO(s->source.file_name);
            CHECK(s->toolchain.cross_compiled);
            CHECK(s->toolchain.glsl330.empty());
            CHECK(s->toolchain.essl300.empty());
            CHECK(s->toolchain.msl.empty());
            CHECK(has_note(s->toolchain.diagnostics,
                           "GLSL 330 and ESSL 300 have no tessellation stages"));
            CHECK(has_note(s->toolchain.diagnostics, "Metal tessellation only as compute kernels"));
        }
        // The vertex and fragment stages cross-compile as the mesh geometry's do.
        for (const StageBuild* s : {&lang.vertex, &lang.fragment}) {
            INFO(s->source.file_name);
            CHECK(s->toolchain.glsl330.find("#version 330") != std::string::npos);
            CHECK(s->toolchain.essl300.find("#version 300 es") != std::string::npos);
            CHECK(s->toolchain.msl.find("#include <metal_stdlib>") != std::string::npos);
        }
    }
}

TEST_CASE("tessellation_factors_are_clamped_to_1_through_64_whatever_tess_max_holds",
          "[tessellation][mesh]") {
    const Graph control = control_graph();
    REQUIRE_FALSE(has_errors(control.diagnostics()));
    // A unit patch at the origin, the eye 10 m above its centre at water level 0: each edge
    // midpoint is sqrt(0.25 + 100) m away.
    const std::vector<std::vector<double>> patch = {
        {-0.5, -0.5}, {0.5, -0.5}, {-0.5, 0.5}, {0.5, 0.5}};
    std::map<std::string, std::vector<double>> u = {{"eye_position", {0.0, 10.0, 0.0}},
                                                    {"water_level", {0.0}},
                                                    {"tess_scale", {40.0}},
                                                    {"tess_max", {16.0}}};
    auto f = factors(control, u, patch);
    const double expected = 40.0 / std::sqrt(100.25);
    for (const char* name : {"outer_0", "outer_1", "outer_2", "outer_3", "inner_0", "inner_1"})
        CHECK(f[name] == Approx(expected).epsilon(1e-6));
    // tess_max beyond the guaranteed 64 is clamped in the shader, not trusted.
    u["tess_scale"] = {1e4};
    u["tess_max"] = {100.0};
    f = factors(control, u, patch);
    for (const char* name : {"outer_0", "outer_1", "outer_2", "outer_3", "inner_0", "inner_1"})
        CHECK(f[name] == 64.0);
    // tess_max 0 (and below) gives 1: the patch is drawn, never with 0 (culled) or less.
    for (double bad : {0.0, -5.0}) {
        u["tess_max"] = {bad};
        f = factors(control, u, patch);
        for (const char* name : {"outer_0", "outer_3", "inner_1"})
            CHECK(f[name] == 1.0);
    }
    // A negative scale gives 1 as well.
    u["tess_max"] = {16.0};
    u["tess_scale"] = {-40.0};
    f = factors(control, u, patch);
    CHECK(f["outer_2"] == 1.0);
    // The eye on an edge's midpoint: the distance floor keeps the quotient finite; the limit.
    u["tess_scale"] = {40.0};
    u["eye_position"] = {0.0, 0.0, -0.5};
    f = factors(control, u, patch);
    CHECK(f["outer_1"] == 16.0);
    CHECK(f["inner_0"] == 16.0);
    // Farther edges are coarser; each inner factor is the larger of the two edges across it.
    u["eye_position"] = {0.0, 1.0, -3.0};
    f = factors(control, u, patch);
    CHECK(f["outer_1"] > f["outer_3"]); // v = 0 is nearer than v = 1
    CHECK(f["inner_0"] == std::max(f["outer_1"], f["outer_3"]));
    CHECK(f["inner_1"] == std::max(f["outer_0"], f["outer_2"]));
    // The shaders hold the clamp.
    const VariantBuild b = tessellated_build("gerstner");
    REQUIRE(b.ok());
    CHECK(b.languages[0].control.source.source.find("clamp(params.tess_max, 1.0, 64.0)") !=
          std::string::npos);
    CHECK(b.languages[1].control.source.source.find("clamp(tess_max, 1.0, 64.0)") !=
          std::string::npos);
}

TEST_CASE("patch_stage_emitters_report_what_a_skeleton_cannot_take", "[tessellation][mesh]") {
    Diagnostics ds;
    {
        // A control graph without its last inner factor.
        Graph g;
        Expr c = varying(g, "corner_0", Type::Vec2);
        for (const char* name : {"outer_0", "outer_1", "outer_2", "outer_3", "inner_0"})
            g.set_output(name, length(c).id());
        emit_tess_control(g, Language::Hlsl, "mesh", "t.tesc.hlsl", "test", ds);
        REQUIRE(has_errors(ds));
        CHECK(ds.back().message.find("needs a float output 'inner_1'") != std::string::npos);
    }
    {
        // An evaluation graph reading an input the skeleton does not define.
        Graph g;
        Expr p = varying(g, "grid_uv", Type::Vec2);
        g.set_output("position", vec4(p, p).id());
        ds.clear();
        emit_tess_evaluation(g, Language::Glsl, "mesh", "t.tese.glsl", "test", ds);
        REQUIRE(has_errors(ds));
        CHECK(ds.back().message.find("reads the input 'grid_uv' (vec2)") != std::string::npos);
        CHECK(ds.back().message.find("expected grid_xz (vec2)") != std::string::npos);
    }
    {
        // A stage reading a parameter the shared block lacks.
        const MeshStages s = build_mesh_stages("tessellated", "sum_of_sines");
        ds.clear();
        const std::vector<Parameter> block = shared_block_parameters({&s.evaluation}, ds);
        REQUIRE_FALSE(has_errors(ds));
        emit_tess_control(s.control, Language::Glsl, "mesh", "t.tesc.glsl", "test", ds,
                          PatchStageOptions{nullptr, &block});
        REQUIRE(has_errors(ds));
        CHECK(ds.front().message.find("parameter 'tess_scale' is read by this stage and missing "
                                      "from the shared parameter block") != std::string::npos);
    }
    {
        // Two stages declaring one parameter differently.
        Graph a, b;
        Expr x = uniform(a, {.name = "tess_scale",
                             .type = Type::Float,
                             .default_value = {40.0},
                             .max = 1e4,
                             .unit = "m"});
        a.set_output("o", x.id());
        Expr y = uniform(b, {.name = "tess_scale",
                             .type = Type::Float,
                             .default_value = {20.0},
                             .max = 1e4,
                             .unit = "m"});
        b.set_output("o", y.id());
        ds.clear();
        const std::vector<Parameter> block = shared_block_parameters({&a, &b}, ds);
        CHECK(block.size() == 1);
        REQUIRE(has_errors(ds));
        CHECK(ds.front().message.find("tess_scale") != std::string::npos);
    }
}

TEST_CASE("reflection_json_round_trips_the_tessellation_stages", "[tessellation][reflection]") {
    const VariantBuild b = tessellated_build("sum_of_sines");
    REQUIRE(b.ok());
    for (const StageBuild* s : {&b.languages[1].control, &b.languages[1].evaluation}) {
        const std::string text = reflection_to_json(s->toolchain.reflection);
        CHECK(text.find(s->source.stage == ShaderStage::TessControl
                            ? "\"stage\": \"tess_control\""
                            : "\"stage\": \"tess_evaluation\"") != std::string::npos);
        std::string error;
        const auto back = reflection_from_json(text, &error);
        INFO(error);
        REQUIRE(back);
        CHECK(back->stage == s->source.stage);
        CHECK(reflection_to_json(*back) == text);
    }
    CHECK(std::string(stage_tag(ShaderStage::TessControl)) == "tesc");
    CHECK(std::string(stage_tag(ShaderStage::TessEvaluation)) == "tese");
    CHECK(std::string(file_extension(Language::Hlsl, ShaderStage::TessControl)) == "tesc.hlsl");
    CHECK(std::string(file_extension(Language::Glsl, ShaderStage::TessEvaluation)) == "tese.glsl");
}
