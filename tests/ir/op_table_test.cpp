// The op table (generator/ir/core/op_table.h) against the rooms that read it: every operation
// make() builds is typed, evaluated by the CPU evaluator, bounded by the interval rules (the
// CPU's values inside the bounds), and spelled by both back ends so that glslang compiles it.
// A new row the rooms do not handle fails here, not in a water shader.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "watergen/ir/core/dsl.h"
#include "watergen/ir/core/op_table.h"
#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/ir/emit/emitter.h"
#include "watergen/ir/fold/interval.h"
#include "watergen/toolchain/glslang_stage.h"

using namespace watergen;

namespace {

// Varyings lie in [kLo, kHi]: positive, so log, sqrt, pow and rsqrt are defined.
constexpr double kLo = 0.2, kHi = 0.9;
constexpr size_t kLanes = 64; // 16 quads, for the derivatives

// One operand of type `t`, a varying (bools: a comparison of two).
Expr operand(Graph& g, Type t, int k) {
    const std::string name = "a" + std::to_string(k);
    if (t == Type::Bool) return varying(g, name, Type::Float) < varying(g, name + "b", Type::Float);
    if (t == Type::Texture2D) {
        TextureInput input;
        input.name = "t";
        return texture(g, input);
    }
    return varying(g, name, t);
}

// The operand types an op of this typing is made with.
std::vector<Type> operand_types(const OpInfo& op) {
    const auto n = [&](Type t) { return std::vector<Type>(static_cast<size_t>(op.arity), t); };
    switch (op.typing) {
    case OpTyping::Compare:
        return n(Type::Float);
    case OpTyping::Logic:
    case OpTyping::LogicNot:
        return n(Type::Bool);
    case OpTyping::Select:
        return {Type::Bool, Type::Vec3, Type::Vec3};
    case OpTyping::Refract:
        return {Type::Vec3, Type::Vec3, Type::Float};
    case OpTyping::Sample:
        return {Type::Texture2D, Type::Vec2};
    case OpTyping::SampleLevel:
        return {Type::Texture2D, Type::Vec2, Type::Float};
    case OpTyping::Construct:
        return {Type::Float, Type::Vec2};
    default:
        return n(Type::Vec3);
    }
}

Expr build(Graph& g, const OpInfo& op) {
    const std::vector<Type> types = operand_types(op);
    std::vector<Expr> a;
    for (size_t i = 0; i < types.size(); ++i)
        a.push_back(operand(g, types[i], static_cast<int>(i)));
    switch (a.size()) {
    case 1:
        return make(op.op, {a[0]});
    case 2:
        return make(op.op, {a[0], a[1]});
    default:
        return make(op.op, {a[0], a[1], a[2]});
    }
}

// The fragment output: the result's components (a bool as 0 or 1) in a vec4.
Expr as_color(Expr r) {
    if (r.type() == Type::Bool) r = select(r, constant(r.graph(), 1.0), constant(r.graph(), 0.0));
    switch (r.type()) {
    case Type::Float:
        return splat(r, Type::Vec4);
    case Type::Vec2:
        return vec4(vec3(r, constant(r.graph(), 0.0)), constant(r.graph(), 1.0));
    case Type::Vec3:
        return vec4(r, constant(r.graph(), 1.0));
    default:
        return r;
    }
}

// Bounds of node `id` with every varying in [kLo, kHi].
Intervals bounds(const Graph& g, uint32_t id) {
    const Node& n = g.node(id);
    if (n.op == Op::Varying)
        return Intervals(static_cast<size_t>(component_count(n.type)), make_interval(kLo, kHi));
    std::vector<Intervals> args;
    std::vector<Type> types;
    for (uint32_t a : n.args) {
        args.push_back(bounds(g, a));
        types.push_back(g.node(a).type);
    }
    std::vector<const Intervals*> ptrs;
    for (const auto& a : args)
        ptrs.push_back(&a);
    return node_intervals(n, ptrs, types);
}

EvalInputs inputs(const Graph& g, const std::vector<float>& texels) {
    EvalInputs in;
    in.lanes = kLanes;
    in.textures["t"] = TextureView{.width = 2, .height = 2, .rgba = texels.data()};
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(kLo, kHi);
    for (uint32_t id : g.live_nodes()) {
        const Node& n = g.node(id);
        if (n.op != Op::Varying) continue;
        auto& v = in.varyings[n.name];
        v.resize(kLanes * static_cast<size_t>(component_count(n.type)));
        for (double& x : v)
            x = u(rng);
    }
    return in;
}

} // namespace

TEST_CASE("every_op_has_one_row_in_the_enum's_order_with_a_name_of_its_own", "[op_table]") {
    std::set<std::string> names;
    size_t i = 0;
    for (const OpInfo* op = op_table_begin(); op != op_table_end(); ++op, ++i) {
        CHECK(static_cast<size_t>(op->op) == i);
        CHECK(names.insert(op->name).second);
        CHECK(std::string(op_name(op->op)) == op->name);
        CHECK(is_leaf(op->op) == (op->kind == OpKind::Input || op->kind == OpKind::BodyInput));
        // Only two-operand ops are written between their operands.
        if (op->infix) CHECK(op->arity == 2);
    }
    CHECK(i == static_cast<size_t>(kLastOp) + 1);
}

TEST_CASE("every_op_make_builds_is_typed_evaluated_bounded_and_compiled", "[op_table]") {
    const std::vector<float> texels = {0.1f, 0.2f, 0.3f, 1.0f, 0.4f, 0.5f, 0.6f, 1.0f,
                                       0.7f, 0.8f, 0.9f, 1.0f, 0.3f, 0.6f, 0.9f, 1.0f};
    int made = 0;
    for (const OpInfo* op = op_table_begin(); op != op_table_end(); ++op) {
        if (op->typing == OpTyping::NotMade) continue;
        ++made;
        INFO(op->name);
        Graph g;
        const Expr r = build(g, *op);
        REQUIRE(g.diagnostics().empty());
        REQUIRE(r.type() != Type::Error);
        REQUIRE(g.node(r.id()).op == op->op);
        g.set_output("color", as_color(r).id());

        // The CPU evaluator computes it, finite for operands in [kLo, kHi]; the result is the
        // output's first components.
        const EvalResult v = evaluate(g, "color", inputs(g, texels), EvalPrecision::Double);
        REQUIRE(v.ok());
        for (double x : v.values)
            REQUIRE(std::isfinite(x));

        // The interval rule holds every value the CPU computed (an op whose bounds are the
        // caller's, a texture sample, gets unknown ones).
        const Intervals b = bounds(g, r.id());
        REQUIRE(b.size() == static_cast<size_t>(component_count(r.type())));
        REQUIRE(v.components == 4);
        for (size_t l = 0; l < kLanes; ++l)
            for (size_t c = 0; c < b.size(); ++c) {
                const double x = v.values[l * 4 + c];
                CHECK(x >= b[c].lo);
                CHECK(x <= b[c].hi);
            }

        // Both back ends spell it, with the table's name for the call, and glslang compiles it.
        for (const Language language : {Language::Glsl, Language::Hlsl}) {
            Diagnostics ds;
            const EmittedShader s = emit_fragment(g, language, "op.frag", "op", ds);
            std::string messages;
            for (const auto& d : ds)
                messages += d.message + "\n";
            INFO(messages);
            REQUIRE_FALSE(has_errors(ds));
            const char* spelled = language == Language::Hlsl && op->hlsl ? op->hlsl
                                  : op->glsl                             ? op->glsl
                                                                         : nullptr;
            if (spelled) CHECK(s.source.find(std::string(spelled) + "(") != std::string::npos);
            CompileRequest request;
            request.language =
                language == Language::Glsl ? SourceLanguage::Glsl : SourceLanguage::Hlsl;
            request.source = s.source;
            request.file_name = "op.frag";
            const SpirvResult spirv = compile_to_spirv(request);
            std::string log;
            for (const auto& d : spirv.diagnostics)
                log += std::to_string(d.line) + ": " + d.message + "\n";
            INFO(s.source);
            INFO(log);
            CHECK(spirv.ok());
        }
    }
    // Every op but the leaves, swizzle and splat, matrix * vector (make(Op::Mul) makes it), the
    // loop and switch ops and the element read.
    CHECK(made == 47);
}
