// Parameters as specialization constants: ids, values, the block without them, and how each
// language declares and reads them.
#include <catch2/catch.hpp>

#include <string>

#include "specialization_support.h"
#include "watergen/ir/emit/emitter.h"
#include "watergen/ir/emit/specialization.h"

using namespace watergen;

namespace {

bool has_line(const std::string& source, const std::string& line) {
    return source.find("\n" + line + "\n") != std::string::npos;
}

Parameter float_parameter(const char* name, double value) {
    return {.name = name, .type = Type::Float, .default_value = {value}, .max = 1.0};
}

} // namespace

TEST_CASE("specialization_ids_follow_declaration_and_component_order", "[specialization]") {
    Parameter a = float_parameter("a", 0.5);
    Parameter v = test::tint_parameter();
    Parameter b = float_parameter("b", 0.75);
    a.specialization = b.specialization = true;
    Diagnostics ds;
    const auto slots = specialization_slots({a, v, float_parameter("kept", 1.0), b}, ds);
    CHECK(ds.empty());
    REQUIRE(slots.size() == 5);
    const char* names[] = {"a", "tint_x", "tint_y", "tint_z", "b"};
    const double defaults[] = {0.5, 0.25, -0.5, 2.0, 0.75};
    for (uint32_t i = 0; i < 5; ++i) {
        CHECK(slots[i].id == i);
        CHECK(slots[i].name == names[i]);
        CHECK(slots[i].default_value == defaults[i]);
    }
    CHECK(slots[2].parameter == "tint");
    CHECK(slots[2].component == 1);
    CHECK(slots[2].min == -1.0);
    CHECK(slots[2].max == 4.0);
}

TEST_CASE("specialization_values_take_overrides_of_the_right_size", "[specialization]") {
    Parameter a = float_parameter("a", 0.5);
    a.specialization = true;
    Diagnostics ds;
    const auto slots = specialization_slots({a, test::tint_parameter()}, ds);
    const auto defaults = specialization_values(slots);
    CHECK(defaults == std::map<uint32_t, float>{{0, 0.5f}, {1, 0.25f}, {2, -0.5f}, {3, 2.0f}});
    const auto set = specialization_values(slots, {{"tint", {0.1, 0.2, 0.3}}, {"a", {1.0, 2.0}}});
    CHECK(set == std::map<uint32_t, float>{{0, 0.5f}, {1, 0.1f}, {2, 0.2f}, {3, 0.3f}});
}

TEST_CASE("the_uniform_block_leaves_out_specialized_parameters", "[specialization]") {
    Diagnostics ds;
    const UniformLayout l = layout_uniforms({test::tint_parameter(), test::gain_parameter()}, ds);
    CHECK(ds.empty());
    REQUIRE(l.members.size() == 1);
    CHECK(l.members[0].name == "gain");
    CHECK(l.members[0].offset == 0);
    CHECK(l.size == 16);
}

TEST_CASE("a_matrix_cannot_be_a_specialization_constant", "[specialization]") {
    Parameter m{.name = "m",
                .type = Type::Mat3,
                .default_value = std::vector<double>(9, 0.0),
                .max = 1,
                .origin = "node.m"};
    m.specialization = true;
    Diagnostics ds;
    CHECK(specialization_slots({m}, ds).empty());
    REQUIRE(ds.size() == 1);
    CHECK(ds[0].node == "node.m");
}

TEST_CASE("both_languages_declare_constants_and_compose_vectors", "[specialization]") {
    const struct {
        Language language;
        std::vector<std::string> lines;
    } cases[] = {
        {Language::Glsl,
         {"layout(constant_id = 0) const float tint_x = 0.25;",
          "layout(constant_id = 1) const float tint_y = (-0.5);",
          "layout(constant_id = 2) const float tint_z = 2.0;",
          "const vec3 tint = vec3(tint_x, tint_y, tint_z);", "    layout(offset = 0) float gain;"}},
        {Language::Hlsl,
         {"[[vk::constant_id(0)]] const float tint_x = 0.25;",
          "[[vk::constant_id(2)]] const float tint_z = 2.0;",
          "static const float3 tint = {tint_x, tint_y, tint_z};",
          "    float gain : packoffset(c0.x);"}}};
    for (const auto& c : cases) {
        INFO(to_string(c.language));
        Diagnostics ds;
        const EmittedShader s = emit_fragment(test::tint_graph(), c.language, "f", "k", ds);
        CHECK(ds.empty());
        for (const auto& line : c.lines)
            CHECK(has_line(s.source, line));
        CHECK(s.interface.uniforms.members.size() == 1);
        CHECK(s.interface.specialization.size() == 3);
    }
    Diagnostics ds;
    const std::string glsl = emit_fragment(test::tint_graph(), Language::Glsl, "f", "k", ds).source;
    CHECK(glsl.find("params.gain") != std::string::npos);
    CHECK(glsl.find("params.tint") == std::string::npos);
}

TEST_CASE("emit_options_make_named_parameters_constants", "[specialization]") {
    Diagnostics ds;
    EmitOptions options;
    options.specialization_constants = {"gain"};
    const EmittedShader s =
        emit_fragment(test::tint_graph(), Language::Glsl, "f", "k", ds, options);
    CHECK(ds.empty());
    // Declaration order: tint (0..2) before gain (3). Nothing is left in the block.
    CHECK(has_line(s.source, "layout(constant_id = 3) const float gain = 2.0;"));
    CHECK(s.source.find("WaterParams") == std::string::npos);
    CHECK(s.source.find("params.") == std::string::npos);

    options.specialization_constants = {"gian"};
    Diagnostics unknown;
    emit_fragment(test::tint_graph(), Language::Glsl, "f", "k", unknown, options);
    REQUIRE(unknown.size() == 1);
    CHECK(unknown[0].message == "specialization constant 'gian' names no parameter of the shader");
}

TEST_CASE("a_parameter_declared_again_with_another_specialization_is_an_error",
          "[specialization]") {
    Graph g;
    Parameter tint = test::tint_parameter();
    g.declare_parameter(tint);
    CHECK(g.diagnostics().empty());
    tint.specialization = false;
    g.declare_parameter(tint);
    CHECK(g.diagnostics().size() == 1);
}
