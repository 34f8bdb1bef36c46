#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <unordered_set>

#include "doc_text.h"
#include "watergen/plan/covering_array.h"
#include "watergen/plan/variant_space.h"

using namespace watergen;

namespace {

size_t combinations(const VariantSpace& s) {
    size_t n = 1;
    for (const auto& c : s.choices)
        n *= c.size();
    return n;
}

} // namespace

TEST_CASE("the_full_space_has_3502080_variants", "[space]") {
    // The one pinned size of the space: 4*5*4*4*4*3*4*5*2*2 = 307200 combinations less the
    // analytic normals without sines or Gerstner and crest/both foam on flat water gave 238080
    // before caustics; caustics none and texture take any of them, area_ratio and photon_splat
    // the 122880 with sum_of_sines or Gerstner waves: 2 * 238080 + 2 * 122880 = 721920; and
    // scene_input doubles it to 1443840. The geometry axis adds 2058240 meshes (waves flat,
    // sum_of_sines or gerstner) and tessellated meshes (sum_of_sines or gerstner). Adding a
    // choice changes it: update it here; every other count is derived from the registry.
    CHECK(count_variants(full_space()) == 3502080);
    std::set<std::string> keys;
    enumerate(full_space(), [&](const Variant& v) { keys.insert(v.key()); });
    CHECK(keys.size() == count_variants(full_space()));
}

TEST_CASE("every_combination_is_visited_exactly_when_no_rule_breaks", "[space]") {
    // Exhaustive: the space is a pure function of axes x choices and the rules.
    // Hashed: a tree of 3.5 million keys took most of this test's 20 s.
    std::unordered_set<std::string> visited;
    visited.reserve(count_variants(full_space()));
    enumerate(full_space(), [&](const Variant& v) { visited.insert(v.key()); });
    VariantSpace unconstrained = full_space();
    unconstrained.rules.clear();
    size_t all = 0, valid = 0, misplaced = 0, unchecked = 0;
    enumerate(unconstrained, [&](const Variant& v) {
        ++all;
        const bool ok = !broken_rule(builtin_rules(), v);
        valid += ok;
        unchecked += ok != !check_constraints(v);
        misplaced += ok != (visited.count(v.key()) == 1);
    });
    CHECK(all == combinations(full_space()));
    CHECK(valid == visited.size());
    CHECK(valid < all); // the built-in rules do rule variants out
    CHECK(unchecked == 0);
    CHECK(misplaced == 0);
}

TEST_CASE("builtin_rules_are_the_requirements_of_the_choices", "[space]") {
    size_t requirements = 0;
    for (const auto& a : axes())
        for (const auto& c : a.choices)
            requirements += c.requirements.size();
    const auto rules = builtin_rules();
    CHECK(rules.size() == requirements);
    Variant v = default_variant();
    REQUIRE_FALSE(set_choice(v, "normals", "analytic"));
    CHECK(*check_constraints(v) ==
          "normals=analytic requires waves in {sum_of_sines, gerstner} (analytic normals are "
          "the derivatives of a closed-form wave model); got waves=flat");
    REQUIRE_FALSE(set_choice(v, "normals", "flat"));
    REQUIRE_FALSE(set_choice(v, "foam", "both"));
    CHECK(*check_constraints(v) ==
          "foam=both requires waves in {sum_of_sines, gerstner, heightmap_march, "
          "heightmap_march_converged} (crest foam needs wave heights); got waves=flat");
}

TEST_CASE("requires_and_excludes_rules", "[space]") {
    VariantSpace s = full_space();
    for (auto& c : s.choices)
        c.resize(1);                                     // one choice per axis ...
    s.offered("fresnel") = {"none", "schlick", "exact"}; // ... but three Fresnel terms
    s.offered("precision") = {"full", "half"};           // and two precisions
    CHECK(count_variants(s) == 6);
    s.rules.push_back({Rule::Kind::Excludes,
                       "precision",
                       "half",
                       "fresnel",
                       {"exact"},
                       "reference only",
                       "m.json:3:4"});
    CHECK(count_variants(s) == 5);
    s.rules.push_back({Rule::Kind::Requires,
                       "fresnel",
                       "none",
                       "precision",
                       {"half"},
                       "cheapest on mobile only",
                       ""});
    CHECK(count_variants(s) == 4);
    Variant v = default_variant();
    REQUIRE_FALSE(set_choice(v, "fresnel", "exact"));
    REQUIRE_FALSE(set_choice(v, "precision", "half"));
    const auto broken = broken_rule(s.rules, v);
    REQUIRE(broken);
    CHECK(*broken == "precision=half excludes fresnel in {exact} (reference only); got "
                     "fresnel=exact [m.json:3:4]");
    REQUIRE_FALSE(set_choice(v, "precision", "full"));
    REQUIRE_FALSE(set_choice(v, "fresnel", "none"));
    CHECK(
        *broken_rule(s.rules, v) ==
        "fresnel=none requires precision in {half} (cheapest on mobile only); got precision=full");
}

TEST_CASE("short_hash_is_16_hex_digits_stable_and_distinct", "[space]") {
    const std::string h = default_variant().short_hash();
    CHECK(h.size() == 16);
    CHECK(h.find_first_not_of("0123456789abcdef") == std::string::npos);
    CHECK(h == default_variant().short_hash());
    std::unordered_set<std::string> hashes;
    hashes.reserve(count_variants(full_space()));
    enumerate(full_space(), [&](const Variant& v) { hashes.insert(v.short_hash()); });
    CHECK(hashes.size() == count_variants(full_space()));
}

TEST_CASE("user_guide_axis_table_is_the_registry's", "[space][docs]") {
    // docs/user-guide.md's table under "## Axes" is axes_markdown_table(); regenerate it from
    // there.
    const std::string text = test::user_guide_text();
    const size_t section = text.find("\n## Axes\n");
    REQUIRE(section != std::string::npos);
    const size_t start = text.find("| axis | choices |", section);
    REQUIRE(start != std::string::npos);
    const size_t end = text.find("\n\n", start);
    REQUIRE(end != std::string::npos);
    CHECK(text.substr(start, end + 1 - start) == axes_markdown_table());
}

TEST_CASE("the_docs_count_and_name_the_registry's_axes", "[space][docs]") {
    // The user guide's "Thirteen axes" is the registry's count; the README's opening names
    // every axis (its words: "scene_input" as "scene input", Fresnel capitalised).
    const std::vector<std::string> words = {
        "Zero",     "One",     "Two",     "Three",     "Four",     "Five",    "Six",
        "Seven",    "Eight",   "Nine",    "Ten",       "Eleven",   "Twelve",  "Thirteen",
        "Fourteen", "Fifteen", "Sixteen", "Seventeen", "Eighteen", "Nineteen"};
    REQUIRE(axes().size() < words.size());
    CHECK(test::user_guide_prose().find(words[axes().size()] +
                                        " axes, one choice each per variant") != std::string::npos);
    const std::string readme = test::readme_prose();
    const size_t start = readme.find("as a choice per feature axis (");
    REQUIRE(start != std::string::npos);
    const std::string list = readme.substr(start, readme.find(')', start) - start);
    for (const auto& axis : axes()) {
        std::string name = axis.name;
        std::replace(name.begin(), name.end(), '_', ' ');
        if (name == "fresnel") name = "Fresnel";
        INFO("README's opening list of axes: " << list);
        CHECK(list.find(name) != std::string::npos);
    }
}

TEST_CASE("user_guide_states_the_size_of_the_space", "[space][docs]") {
    const std::string text = test::user_guide_text();
    const std::string size = std::to_string(count_variants(full_space()));
    CHECK(text.find("The valid space has " + size + " variants") != std::string::npos);
    CHECK(text.find("Of the " + size + " variants of the full space") != std::string::npos);
    // The covering set's size, as the user guide's "## Axes" gives it.
    const std::string covering = std::to_string(pairwise_covering_variants().size());
    CHECK(test::user_guide_prose().find("at least one variant, " + covering + " variants in all") !=
          std::string::npos);
}
