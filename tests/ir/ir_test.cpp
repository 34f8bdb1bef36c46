#include <catch2/catch.hpp>

#include "watergen/ir/core/dsl.h"

using namespace watergen;

TEST_CASE("identical_expressions_are_one_node", "[ir]") {
    Graph g;
    Expr a = varying(g, "a", Type::Vec3);
    Expr b = varying(g, "b", Type::Vec3);
    Expr s1 = dot(a, b) * 2.0;
    Expr s2 = dot(a, b) * 2.0;
    CHECK(s1.id() == s2.id());
    CHECK(dot(a, b).id() != dot(b, a).id()); // no algebraic canonicalisation: operand order is kept
}

TEST_CASE("naming_hint_does_not_split_equal_nodes", "[ir]") {
    Graph g;
    Expr a = varying(g, "a", Type::Float);
    Expr x = named(a * a, "square");
    Expr y = a * a;
    CHECK(x.id() == y.id());
    CHECK(g.node(y.id()).name == "square");
}

TEST_CASE("live_nodes_skip_what_no_output_reads", "[ir]") {
    Graph g;
    Expr a = varying(g, "a", Type::Float);
    Expr dead = sqrt(a) + 3.0;
    Expr used = a * 2.0;
    g.set_output("out", used.id());
    const auto live = g.live_nodes();
    CHECK(std::find(live.begin(), live.end(), dead.id()) == live.end());
    CHECK(std::find(live.begin(), live.end(), used.id()) != live.end());
    CHECK(std::is_sorted(live.begin(), live.end()));
}

TEST_CASE("nodes_record_the_feature_node_that_built_them", "[ir]") {
    Graph g;
    Expr a = varying(g, "a", Type::Float);
    uint32_t id = 0;
    {
        OriginScope scope(g, "fresnel.schlick");
        id = (a * 5.0).id();
    }
    CHECK(g.node(id).origin == "fresnel.schlick");
    CHECK(g.origin().empty());
}

TEST_CASE("identity_swizzle_is_the_value_itself", "[ir]") {
    Graph g;
    Expr v = varying(g, "v", Type::Vec3);
    CHECK(v.xyz().id() == v.id());
    CHECK(v.xz().type() == Type::Vec2);
}
