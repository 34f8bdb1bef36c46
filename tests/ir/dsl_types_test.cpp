#include <catch2/catch.hpp>

#include "watergen/ir/core/dsl.h"

using namespace watergen;

namespace {
bool mentions(const Diagnostics& ds, const std::string& node, const std::string& text) {
    for (const auto& d : ds)
        if (d.severity == Severity::Error && d.node == node &&
            d.message.find(text) != std::string::npos)
            return true;
    return false;
}
} // namespace

TEST_CASE("vec3_plus_vec2_is_reported_naming_the_node", "[dsl]") {
    Graph g;
    OriginScope scope(g, "foam.shore");
    Expr r = varying(g, "a", Type::Vec3) + varying(g, "b", Type::Vec2);
    CHECK(r.type() == Type::Error);
    REQUIRE(g.diagnostics().size() == 1);
    CHECK(mentions(g.diagnostics(), "foam.shore", "operand types differ (got vec3, vec2)"));
}

TEST_CASE("errors_propagate_without_cascading", "[dsl]") {
    Graph g;
    Expr bad = varying(g, "a", Type::Vec3) + varying(g, "b", Type::Vec2);
    Expr worse = normalize(bad) * 2.0 + 1.0;
    CHECK(worse.type() == Type::Error);
    CHECK(g.diagnostics().size() == 1);
}

TEST_CASE("wrong_arity_is_reported", "[dsl]") {
    Graph g;
    OriginScope scope(g, "test.arity");
    Expr a = varying(g, "a", Type::Float);
    Expr r = make(Op::Mix, {a, a});
    CHECK(r.type() == Type::Error);
    CHECK(mentions(g.diagnostics(), "test.arity", "mix expects 3 arguments, got 2"));
}

TEST_CASE("scalar_broadcasts_in_arithmetic_and_is_splatted_in_intrinsics", "[dsl]") {
    Graph g;
    Expr v = varying(g, "v", Type::Vec3);
    Expr s = varying(g, "s", Type::Float);
    CHECK((v * s).type() == Type::Vec3);
    CHECK((s - v).type() == Type::Vec3);
    Expr m = mix(v, v * 2.0, s);
    REQUIRE(m.type() == Type::Vec3);
    const Node& n = g.node(m.id());
    CHECK(g.node(n.args[2]).op == Op::Splat);
    CHECK(g.diagnostics().empty());
}

TEST_CASE("intrinsics_check_their_operands", "[dsl]") {
    Graph g;
    OriginScope scope(g, "test.intrinsics");
    Expr v2 = varying(g, "v2", Type::Vec2);
    Expr v3 = varying(g, "v3", Type::Vec3);
    Expr f = varying(g, "f", Type::Float);
    CHECK(dot(v3, v2).type() == Type::Error);
    CHECK(cross(v2, v2).type() == Type::Error);
    CHECK(refract(v3, v3, v2).type() == Type::Error);
    CHECK(select(f, v3, v3).type() == Type::Error);
    CHECK(v2.swizzle("xyz").type() == Type::Error);
    CHECK(vec4(v3, v2).type() == Type::Error);
    CHECK(g.diagnostics().size() == 6);
    CHECK(mentions(g.diagnostics(), "test.intrinsics", "swizzle 'xyz' reads past a vec2"));
    CHECK(dot(v3, v3).type() == Type::Float);
    CHECK(refract(v3, v3, f).type() == Type::Vec3);
    CHECK((mat3(v3, v3, v3) * v3).type() == Type::Vec3);
}

TEST_CASE("parameters_declared_twice_must_agree", "[dsl]") {
    Graph g;
    uniform(g, {.name = "k", .type = Type::Float, .default_value = {1.0}, .max = 2});
    uniform(g, {.name = "k", .type = Type::Float, .default_value = {1.0}, .max = 2});
    CHECK(g.diagnostics().empty());
    uniform(g, {.name = "k", .type = Type::Vec3, .default_value = {1.0, 1.0, 1.0}, .max = 2});
    CHECK(g.diagnostics().size() == 1);
}
