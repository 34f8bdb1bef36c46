#include <catch2/catch.hpp>

#include <set>

#include "watergen/plan/variant_space.h"

using namespace watergen;

TEST_CASE("full_space_has_238080_variants_the_same_as_for_each_variant", "[space]") {
    std::vector<std::string> ours, core;
    enumerate(full_space(), [&](const Variant& v) { ours.push_back(v.key()); });
    for_each_variant([&](const Variant& v) { core.push_back(v.key()); });
    CHECK(ours.size() == 238080);
    CHECK(count_variants(full_space()) == 238080);
    CHECK(ours == core); // same order too
}

TEST_CASE("every_combination_is_visited_exactly_when_no_rule_breaks", "[space]") {
    // Exhaustive over all 307200 combinations: the space is a pure function of axes x choices
    // and the rules, and broken_rule agrees with the core's check_constraints.
    std::set<std::string> visited;
    enumerate(full_space(), [&](const Variant& v) { visited.insert(v.key()); });
    const auto rules = builtin_rules();
    VariantSpace unconstrained = full_space();
    unconstrained.rules.clear();
    size_t all = 0, valid = 0, disagreements = 0, misplaced = 0;
    enumerate(unconstrained, [&](const Variant& v) {
        ++all;
        const bool ok = !broken_rule(rules, v);
        valid += ok;
        disagreements += ok != !check_constraints(v);
        misplaced += ok != (visited.count(v.key()) == 1);
    });
    CHECK(all == 307200);
    CHECK(valid == 238080);
    CHECK(disagreements == 0);
    CHECK(misplaced == 0);
}

TEST_CASE("requires_and_excludes_rules", "[space]") {
    VariantSpace s = full_space();
    for (auto& c : s.choices) c.resize(1); // one choice per axis ...
    s.choices[0] = {"none", "schlick", "exact"};  // ... but three Fresnel terms
    s.choices[9] = {"full", "half"};              // and two precisions
    CHECK(count_variants(s) == 6);
    s.rules.push_back({Rule::Kind::Excludes, "precision", "half", "fresnel", {"exact"}, "reference only", "m.json:3:4"});
    CHECK(count_variants(s) == 5);
    s.rules.push_back({Rule::Kind::Requires, "fresnel", "none", "precision", {"half"}, "cheapest on mobile only", ""});
    CHECK(count_variants(s) == 4);
    Variant v = default_variant();
    v.choices = {"exact", "none", "none", "none", "none", "none", "flat", "flat", "hard", "half"};
    const auto broken = broken_rule(s.rules, v);
    REQUIRE(broken);
    CHECK(*broken == "precision=half excludes fresnel in {exact} (reference only); got fresnel=exact [m.json:3:4]");
    v.choices[9] = "full";
    v.choices[0] = "none";
    CHECK(*broken_rule(s.rules, v) == "fresnel=none requires precision in {half} (cheapest on mobile only); got precision=full");
}

TEST_CASE("short_hash_is_16_hex_digits_stable_and_distinct", "[space]") {
    const std::string h = default_variant().short_hash();
    CHECK(h.size() == 16);
    CHECK(h.find_first_not_of("0123456789abcdef") == std::string::npos);
    CHECK(h == default_variant().short_hash());
    std::set<std::string> hashes;
    enumerate(full_space(), [&](const Variant& v) { hashes.insert(v.short_hash()); });
    CHECK(hashes.size() == 238080);
}
