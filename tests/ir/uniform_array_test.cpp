// Array parameters: std140 / packoffset layout (one 16-byte register per element), packing,
// emission in both languages, element reads in the CPU evaluator, and what is refused.
#include <catch2/catch.hpp>

#include <cstring>

#include "watergen/ir/core/dsl.h"
#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/ir/emit/emitter.h"
#include "watergen/ir/emit/uniform_layout.h"
#include "watergen/ir/fold/ir_fold.h"

using namespace watergen;

namespace {

Parameter array_of(const char* name, Type t, uint32_t size, double first = 0.0) {
    Parameter p{.name = name, .type = t, .min = -10, .max = 10};
    p.array_size = size;
    for (size_t i = 0; i < value_count(p); ++i)
        p.default_value.push_back(first + static_cast<double>(i));
    return p;
}

Parameter scalar(const char* name, double v) {
    return {.name = name, .type = Type::Float, .default_value = {v}, .min = -10, .max = 10};
}

const UniformSlot* slot_of(const UniformLayout& l, const std::string& name) {
    for (const auto& m : l.members)
        if (m.name == name) return &m;
    return nullptr;
}

float float_at(const std::vector<uint8_t>& bytes, size_t offset) {
    float f = 0;
    std::memcpy(&f, bytes.data() + offset, 4);
    return f;
}

// s = sum over the elements e of waves[e].x * e + offsets[e], as a loop over the array.
Graph summing_graph() {
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    const Parameter waves = array_of("waves", Type::Vec4, 4, 1.0);
    const Parameter offsets = array_of("offsets", Type::Float, 3, 0.5);
    const auto r = loop(g, 4, {x}, [&](Expr i, const std::vector<Expr>& c) {
        return LoopStep{{c[0] + element(waves, i).x() * i + element(offsets, i)}, Expr()};
    });
    g.set_output("s", r[0].id());
    return g;
}

} // namespace

TEST_CASE("arrays_take_one_register_per_element_and_nothing_shares_them", "[layout][array]") {
    Diagnostics ds;
    const auto l = layout_uniforms({scalar("a", 1.0), array_of("gains", Type::Float, 3),
                                    array_of("dirs", Type::Vec2, 2), scalar("b", 2.0)},
                                   ds);
    REQUIRE(ds.empty());
    const UniformSlot* gains = slot_of(l, "gains");
    const UniformSlot* dirs = slot_of(l, "dirs");
    REQUIRE(gains);
    REQUIRE(dirs);
    // The larger array first, each at a register boundary; the scalars after both.
    CHECK(gains->offset == 0);
    CHECK(gains->array_size == 3);
    CHECK(dirs->offset == 48);
    CHECK(dirs->array_size == 2);
    CHECK(slot_of(l, "a")->offset == 80);
    CHECK(slot_of(l, "b")->offset == 84);
    CHECK(slot_of(l, "a")->array_size == 0);
    CHECK(l.size == 96);
}

TEST_CASE("pack_writes_array_elements_sixteen_bytes_apart", "[layout][array]") {
    Diagnostics ds;
    const std::vector<Parameter> params = {array_of("dirs", Type::Vec3, 2, 1.0), scalar("s", 9.0)};
    const auto l = layout_uniforms(params, ds);
    REQUIRE(l.size == 48);
    const auto bytes = pack_uniforms(l, params);
    CHECK(float_at(bytes, 0) == 1.0f);
    CHECK(float_at(bytes, 8) == 3.0f);
    CHECK(float_at(bytes, 12) == 0.0f); // element padding, not the scalar
    CHECK(float_at(bytes, 16) == 4.0f);
    CHECK(float_at(bytes, 24) == 6.0f);
    CHECK(float_at(bytes, 32) == 9.0f);
    // An override holds every element; one of another size is ignored.
    const auto over = pack_uniforms(l, params, {{"dirs", {7, 7, 7, 8, 8, 8}}});
    CHECK(float_at(over, 16) == 8.0f);
    const auto wrong = pack_uniforms(l, params, {{"dirs", {7, 7, 7}}});
    CHECK(float_at(wrong, 16) == 4.0f);
}

TEST_CASE("array_elements_are_read_floored_and_clamped_by_the_cpu", "[eval][array]") {
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    g.set_output("e", element(array_of("gains", Type::Float, 3, 10.0), x).id());
    REQUIRE(g.diagnostics().empty());
    EvalInputs in;
    in.varyings["x"] = {0.0, 1.0, 1.9, 2.0, -3.0, 7.0};
    in.lanes = 6;
    const EvalResult e = evaluate(g, "e", in, EvalPrecision::Double);
    REQUIRE(e.ok());
    CHECK(e.values == std::vector<double>{10.0, 11.0, 11.0, 12.0, 10.0, 12.0});
    in.uniforms["gains"] = {-1.0, -2.0, -3.0};
    CHECK(evaluate(g, "e", in, EvalPrecision::Double).values[2] == -2.0);
}

TEST_CASE("a_loop_sums_the_elements_of_arrays", "[eval][array][loop]") {
    const Graph g = summing_graph();
    REQUIRE(g.diagnostics().empty());
    // The body's reads declare the arrays in the enclosing graph.
    REQUIRE(g.find_parameter("waves"));
    CHECK(g.find_parameter("waves")->array_size == 4);
    EvalInputs in;
    in.varyings["x"] = {0.0, 2.0};
    in.lanes = 2;
    const EvalResult e = evaluate(g, "s", in, EvalPrecision::Double);
    REQUIRE(e.ok());
    // waves[e].x = 1 + 4e; offsets = 0.5, 1.5, 2.5, then clamped to 2.5 at e = 3.
    const double expected = (5.0 * 1 + 9.0 * 2 + 13.0 * 3) + (0.5 + 1.5 + 2.5 + 2.5);
    CHECK(e.values[0] == expected);
    CHECK(e.values[1] == expected + 2.0);
}

TEST_CASE("arrays_are_declared_and_indexed_in_both_languages", "[emit][array]") {
    Graph g;
    Expr uv = varying(g, "v_uv", Type::Vec2);
    const Parameter waves = array_of("waves", Type::Vec4, 4);
    const auto r = loop(g, 4, {uv.x()}, [&](Expr i, const std::vector<Expr>& c) {
        return LoopStep{{c[0] + element(waves, i).y()}, Expr()};
    });
    g.set_output("color", vec4(r[0], uv.y(), uv.x(), constant(g, 1.0)).id());
    Diagnostics ds;
    const EmittedShader glsl = emit_fragment(g, Language::Glsl, "f.glsl", "k", ds);
    const EmittedShader hlsl = emit_fragment(g, Language::Hlsl, "f.hlsl", "k", ds);
    REQUIRE(ds.empty());
    INFO(glsl.source);
    INFO(hlsl.source);
    CHECK(glsl.source.find("layout(offset = 0) vec4 waves[4];") != std::string::npos);
    CHECK(hlsl.source.find("float4 waves[4] : packoffset(c0.x);") != std::string::npos);
    CHECK(glsl.source.find("params.waves[clamp(int(") != std::string::npos);
    CHECK(hlsl.source.find(" waves[clamp(((int)") != std::string::npos);
    REQUIRE(glsl.interface.uniforms.members.size() == 1);
    CHECK(glsl.interface.uniforms.members[0].array_size == 4);
    CHECK(glsl.interface.uniforms.size == 64);
}

TEST_CASE("arrays_are_never_specialization_constants", "[emit][array]") {
    Graph g;
    Expr uv = varying(g, "v_uv", Type::Vec2);
    Expr w = element(array_of("gains", Type::Float, 2), uv.x());
    g.set_output("color", vec4(w, w, w, w).id());
    Diagnostics ds;
    emit_fragment(g, Language::Glsl, "f.glsl", "k", ds, EmitOptions{false, {"gains"}});
    REQUIRE(ds.size() == 1);
    CHECK(ds[0].message.find("'gains' is an array") != std::string::npos);
}

TEST_CASE("misused_arrays_are_diagnostics", "[dsl][array]") {
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    element(scalar("s", 1.0), x);
    REQUIRE(g.diagnostics().size() == 1);
    CHECK(g.diagnostics()[0].message.find("'s' is not an array") != std::string::npos);
    element(array_of("a", Type::Float, 2), vec2(x, x));
    REQUIRE(g.diagnostics().size() == 2);
    CHECK(g.diagnostics()[1].message.find("must be a float") != std::string::npos);
    Parameter short_default = array_of("b", Type::Vec2, 3);
    short_default.default_value.resize(2);
    element(short_default, x);
    REQUIRE(g.diagnostics().size() == 3);
    CHECK(g.diagnostics()[2].message.find("vec2[3] needs 6") != std::string::npos);
    element(array_of("c", Type::Float, 2), x);
    element(array_of("c", Type::Float, 3), x); // same name, other size
    REQUIRE(g.diagnostics().size() == 4);
    CHECK(g.diagnostics()[3].message.find("array size") != std::string::npos);
}

TEST_CASE("the_fold_keeps_a_fixed_array_declared_with_the_fixed_value", "[fold][array]") {
    const Graph g = summing_graph();
    FoldFacts facts;
    facts.fixed["offsets"] = {{-1.0, -2.0, -3.0}, facts.add_fact("offsets fixed", "")};
    const FoldResult folded = fold_graph(g, facts);
    REQUIRE(folded.graph.diagnostics().empty());
    const Parameter* offsets = folded.graph.find_parameter("offsets");
    REQUIRE(offsets);
    CHECK(offsets->array_size == 3);
    CHECK(offsets->default_value == std::vector<double>{-1.0, -2.0, -3.0});
    REQUIRE(folded.graph.find_parameter("waves"));
    // The folded graph computes what the original does with the fixed value...
    EvalInputs in;
    in.varyings["x"] = {0.5};
    in.lanes = 1;
    const double folded_sum = evaluate(folded.graph, "s", in, EvalPrecision::Double).values[0];
    in.uniforms["offsets"] = {-1.0, -2.0, -3.0};
    CHECK(folded_sum == evaluate(g, "s", in, EvalPrecision::Double).values[0]);
    // ... and packs it, element by element.
    Diagnostics ds;
    const UniformLayout l = layout_uniforms(folded.graph.parameters(), ds);
    const auto bytes = pack_uniforms(l, folded.graph.parameters());
    REQUIRE(slot_of(l, "offsets"));
    const uint32_t at = slot_of(l, "offsets")->offset;
    CHECK(float_at(bytes, at) == -1.0f);
    CHECK(float_at(bytes, at + 2 * kArrayStride) == -3.0f);
}
