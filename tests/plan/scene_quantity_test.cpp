// Scene facts reach the IR through typed quantity handles (scene_quantities.h), not through
// the display names of nodes or parameters.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <map>
#include <set>

#include "watergen/ir/core/dsl.h"
#include "watergen/ir/fold/ir_fold.h"
#include "watergen/plan/explain.h"
#include "watergen/plan/scene_pruning.h"
#include "watergen/water/scene_quantities.h"

using namespace watergen;

namespace {

SceneFacts scene(const std::string& name) {
    const char* src = std::getenv("WATERGEN_SOURCE_DIR");
    REQUIRE(src != nullptr);
    Diagnostics ds;
    auto s = load_scene(std::string(src) + "/examples/scenes/" + name + ".json", ds);
    REQUIRE(s);
    return *s;
}

ScenePlan plan(const Material& m, const std::string& name) {
    Diagnostics ds;
    auto p = plan_scene(m, scene(name), ds);
    REQUIRE(p);
    return *p;
}

// `g` with every node named `from` named `to` instead; bindings kept unless `drop_bindings`.
Graph renamed(const Graph& g, const std::string& from, const std::string& to,
              bool drop_bindings = false) {
    Graph out;
    for (const Parameter& p : g.parameters())
        out.declare_parameter(p);
    for (const auto& t : g.textures())
        out.declare_texture(t);
    for (uint32_t id = 0; id < g.size(); ++id) {
        Node n = g.node(id);
        if (n.name == from) n.name = to;
        REQUIRE(out.add(std::move(n)) == id);
    }
    for (const auto& o : g.outputs())
        out.set_output(o.name, o.node);
    if (!drop_bindings)
        for (const auto& b : g.bindings())
            out.bind(b.quantity, b.node);
    return out;
}

// Removed terms as (input node id, name), the renamed temporary under its old name.
std::set<std::pair<uint32_t, std::string>>
removed_terms(const FoldResult& r, const std::string& alias, const std::string& name) {
    std::set<std::pair<uint32_t, std::string>> out;
    for (const auto& t : r.report.removed)
        out.insert({t.node, t.name == alias ? name : t.name});
    return out;
}

std::set<std::string> quantities_of(const FoldFacts& f) {
    std::set<std::string> ids;
    for (const auto& [q, fixed] : f.fixed_quantities)
        ids.insert(std::string(q.id));
    for (const auto& [q, bounds] : f.quantity_ranges)
        ids.insert(std::string(q.id));
    return ids;
}

} // namespace

TEST_CASE("renaming_a_temporary_cannot_turn_a_scene_fold_off", "[quantity]") {
    const Material m = default_material();
    const ScenePlan ocean = plan(m, "open_ocean");
    size_t transmittance_removed = 0;
    for (const Variant& v : ocean.variants) {
        INFO(v.key());
        const Graph g = m.compose(v).fragment;
        const FoldResult as_built = fold_graph(g, ocean.facts);
        const FoldResult renamed_depth =
            fold_graph(renamed(g, "water_depth", "column_height"), ocean.facts);
        CHECK(renamed_depth.report.live_after == as_built.report.live_after);
        CHECK(renamed_depth.report.events.size() == as_built.report.events.size());
        CHECK(removed_terms(renamed_depth, "column_height", "water_depth") ==
              removed_terms(as_built, "", ""));
        for (const auto& t : as_built.report.removed)
            transmittance_removed += t.name == "transmittance";
        // The binding, not the name, carries the depth fact: without it the deep-water terms stay.
        if (v.choice("extinction") == "absorb_scatter") {
            const FoldResult unbound = fold_graph(renamed(g, "", "", true), ocean.facts);
            CHECK(unbound.report.live_after > as_built.report.live_after);
        }
    }
    CHECK(transmittance_removed > 0); // 400 m of water: the transmittance vanishes
}

TEST_CASE("every_scene_fact_about_a_quantity_reaches_the_ir", "[quantity]") {
    // For every variant each example scene reaches: every quantity the plan attaches a fact to
    // is bound in the composed graph (read, or explicitly not read by this variant), never
    // lost; the water depth and the camera are read by every variant, and bindings move
    // with their nodes through the fold.
    const Material m = default_material();
    for (const char* name : {"open_ocean", "harbour_night", "mountain_lake"}) {
        const ScenePlan p = plan(m, name);
        const std::set<std::string> attached = quantities_of(p.facts);
        CHECK(attached.count("water_depth"));
        CHECK(attached.count("eye_position"));
        CHECK(attached.count("time") ==
              (std::string(name) == "mountain_lake")); // static waves only
        std::set<std::string> read, bound_after_fold;
        for (const Variant& v : p.variants) {
            INFO(name << ": " << v.key());
            const FoldResult r = fold_graph(m.compose(v).fragment, p.facts);
            std::set<std::string> reported;
            for (const auto& use : r.report.quantities) {
                const std::string id(use.quantity.id);
                reported.insert(id);
                CHECK(use.reach != QuantityReach::Unbound);
                if (use.reach == QuantityReach::Read) read.insert(id);
                if (id == "water_depth" || id == "eye_position")
                    CHECK(use.reach == QuantityReach::Read);
            }
            CHECK(reported == attached);
            for (const auto& b : r.graph.bindings()) {
                REQUIRE(b.node < r.graph.size());
                bound_after_fold.insert(std::string(b.quantity.id));
            }
        }
        std::set<std::string> expected = attached;
        if (std::string(name) == "harbour_night")
            expected.erase("sun_direction"); // night: no variant has a highlight
        // The time reaches the host, which computes the phase offsets from it (frame.h); no
        // shader reads it.
        expected.erase("time");
        CHECK(read == expected);
        CHECK(bound_after_fold.count(
            "water_depth")); // some variants keep the depth: its binding moved with it
    }
}

TEST_CASE("a_quantity_bound_to_a_renamed_parameter_is_an_error", "[quantity]") {
    Graph g;
    bind(scene_quantity::time, uniform(g, {.name = "seconds",
                                           .type = Type::Float,
                                           .default_value = {0.0},
                                           .max = 10.0,
                                           .unit = "s",
                                           .origin = "test"}));
    REQUIRE(g.diagnostics().size() == 1);
    CHECK(g.diagnostics()[0].message ==
          "quantity 'time' stands for parameter 'time'; bound to parameter 'seconds'");
    CHECK(g.bindings().empty());
    Graph h;
    bind(scene_quantity::water_depth, varying(h, "v", Type::Vec2) * 2.0);
    REQUIRE(h.diagnostics().size() == 1);
    CHECK(h.diagnostics()[0].message == "quantity 'water_depth' is a float; bound to a vec2");
}

TEST_CASE("a_scene_plan_counts_why_it_skips_variants_and_explain_lists_them", "[quantity]") {
    const Material m = default_material();
    const ScenePlan ocean = plan(m, "open_ocean"), lake = plan(m, "mountain_lake");
    REQUIRE(ocean.skipped_groups.size() == 4);
    CHECK(ocean.skipped_groups[0].text().find(
              "caustics=area_ratio: water at least 400 m deep lets at most 2.1e-09 of the "
              "sunlight reach the bottom") == 0);
    CHECK(ocean.skipped_groups[0].variants == 12);
    CHECK(ocean.skipped_groups[1].text().find(
              "foam=shore: no shoreline, so shore foam never shows [") == 0);
    CHECK(ocean.skipped_groups[1].variants == 72);
    CHECK(ocean.skipped_groups[2].text().find(
              "precision=half: the scene targets precision full [") == 0);
    size_t total = 0;
    for (const auto& g : ocean.skipped_groups)
        total += g.variants;
    CHECK(total == ocean.skipped);
    // The groups count the reasons scene_excludes gives, and the unreached variants of two
    // plans are those both exclude, listed with both reasons.
    const ParameterBounds in_ocean = parameter_bounds(m, ocean.fixed),
                          in_lake = parameter_bounds(m, lake.fixed);
    std::map<std::string, size_t> per_reason;
    size_t both = 0;
    UnreachedVariant first;
    enumerate(m.space, [&](const Variant& v) {
        const auto o = scene_excludes(ocean.scene, v, &in_ocean);
        if (!o) return;
        ++per_reason[SkippedGroup{*o, 0}.text()];
        const auto l = scene_excludes(lake.scene, v, &in_lake);
        if (!l) return;
        if (both++ == 0)
            first = {v.key(),
                     {{"open_ocean", SkippedGroup{*o, 0}.text()},
                      {"mountain_lake", SkippedGroup{*l, 0}.text()}}};
    });
    REQUIRE(per_reason.size() == ocean.skipped_groups.size());
    for (const auto& g : ocean.skipped_groups)
        CHECK(per_reason[g.text()] == g.variants);
    const Explanation x = explain_plans(m, {ocean, lake}, "", 4);
    CHECK(x.unreached.size() == both);
    CHECK(x.unreached_count == both);
    REQUIRE_FALSE(x.unreached.empty());
    CHECK(x.unreached[0].key == first.key);
    CHECK(x.unreached[0].reasons == first.reasons);
    // Listing a few counts them all, and lists the same first ones.
    const Explanation few = explain_plans(m, {ocean, lake}, "", 4, 1);
    CHECK(few.unreached_count == both);
    REQUIRE(few.unreached.size() == 1);
    CHECK(few.unreached[0].key == x.unreached[0].key);
    CHECK(few.unreached[0].reasons == x.unreached[0].reasons);
    CHECK(x.scenes[0].folded == 4);
    CHECK(x.scenes[0].step == 4); // 16 variants, 4 folded
}
