// A test build with one extra choice, fresnel=test_constant, registered before the registry's
// first use: the CLI's help, the space, the node catalog, the composition and scene pruning all
// see it, and nothing else names it.
#include <catch2/catch.hpp>

#include <algorithm>

#include "watergen/plan/scene_pruning.h"
#include "watergen/water/node_catalog.h"
#include "watergen/water/surface.h"
#include "watergen/water/water_shader.h"

using namespace watergen;

namespace {

constexpr double kTestReflectance = 0.25;

// Every test calls this first: the registration happens before anything in this executable
// reads the registry.
void register_test_choice() {
    static const std::optional<std::string> error = register_choice(
        "fresnel", {.name = "test_constant",
                    .description = "constant reflectance 0.25 (test build only)",
                    .node = ChoiceNode{{{"c", Type::Float}},
                                       [](Graph& g, const std::vector<Expr>&) {
                                           return constant(g, kTestReflectance);
                                       }},
                    .compose = [](Surface& s) { s.fresnel = constant(s.g, kTestReflectance); },
                    .scene_needs = {{SceneFact::Shoreline, "", "the test constant stays unused"}}});
    INFO(error.value_or(""));
    REQUIRE_FALSE(error.has_value());
}

Variant test_variant() {
    Variant v = default_variant();
    REQUIRE_FALSE(set_choice(v, "fresnel", "test_constant"));
    return v;
}

} // namespace

TEST_CASE("the_help_of_the_axis_lists_the_registered_choice", "[registry]") {
    register_test_choice();
    const std::string help = axis_help(*find_axis("fresnel"));
    const std::string last = "\n  test_constant: constant reflectance 0.25 (test build only)";
    REQUIRE(help.size() > last.size());
    CHECK(help.substr(help.size() - last.size()) == last);
}

TEST_CASE("the_space_grows_by_one_fresnel_choice", "[registry]") {
    register_test_choice();
    VariantSpace without = full_space();
    auto& fresnel = without.offered("fresnel");
    fresnel.erase(std::find(fresnel.begin(), fresnel.end(), "test_constant"));
    const size_t before = count_variants(without);
    // The new choice has no rules: it adds one fresnel choice's share of the space.
    CHECK(count_variants(full_space()) == before + before / fresnel.size());
    CHECK(before % fresnel.size() == 0);
    size_t with_it = 0;
    enumerate(full_space(),
              [&](const Variant& v) { with_it += v.choice("fresnel") == "test_constant"; });
    CHECK(with_it == before / fresnel.size());
}

TEST_CASE("the_catalog_holds_the_registered_node", "[registry]") {
    register_test_choice();
    const CatalogNode* node = find_catalog_node("fresnel.test_constant");
    REQUIRE(node);
    CHECK(node->description == "constant reflectance 0.25 (test build only)");
    REQUIRE(node->inputs.size() == 1);
    CHECK(node->inputs[0].name == "c");
    const Graph g = probe_graph(*node);
    CHECK_FALSE(has_errors(g.diagnostics()));
}

TEST_CASE("the_water_pass_composes_the_registered_choice", "[registry]") {
    register_test_choice();
    const Variant v = test_variant();
    CHECK(v.key().find("fresnel=test_constant,") == 0);
    std::string error;
    const auto parsed = parse_variant_key(v.key(), &error);
    REQUIRE(parsed);
    CHECK(parsed->key() == v.key());
    const WaterShader shader = build_water_shader(v);
    CHECK_FALSE(has_errors(shader.fragment.diagnostics()));
}

TEST_CASE("a_scene_without_the_fact_the_choice_needs_excludes_it", "[registry]") {
    register_test_choice();
    SceneFacts scene;
    scene.reflection_sources = {"cubemap"}; // the default variant's reflection
    scene.shoreline = false;
    const auto excluded = scene_excludes(scene, test_variant());
    REQUIRE(excluded);
    CHECK(excluded->axis == "fresnel");
    CHECK(excluded->choice == "test_constant");
    CHECK(excluded->reason == "no shoreline, so the test constant stays unused");
    CHECK(excluded->where == scene.where.of("shoreline"));
    CHECK_FALSE(scene_excludes(scene, default_variant()));
    scene.shoreline = true;
    CHECK_FALSE(scene_excludes(scene, test_variant()));
}
