#include <catch2/catch.hpp>

#include <set>

#include "watergen/variant.h"

using namespace watergen;

TEST_CASE("variant_key_round_trips", "[variant]") {
    for (const auto& v : all_variants()) {
        std::string error;
        const auto parsed = parse_variant_key(v.key(), &error);
        REQUIRE(parsed);
        CHECK(parsed->key() == v.key());
    }
}

TEST_CASE("every_combination_of_wired_choices_once", "[variant]") {
    size_t expected = 1;
    for (const auto& a : axes()) expected *= a.choices.size();
    const auto all = all_variants();
    CHECK(all.size() == expected);
    std::set<std::string> keys;
    for (const auto& v : all) keys.insert(v.key());
    CHECK(keys.size() == expected);
}

TEST_CASE("unknown_axis_or_choice_names_the_allowed_ones", "[variant]") {
    Variant v = default_variant();
    const auto bad_choice = set_choice(v, "fresnel", "fancy");
    REQUIRE(bad_choice);
    CHECK(*bad_choice == "unknown fresnel choice 'fancy' (choices: none, schlick, exact)");
    const auto bad_axis = set_choice(v, "colour", "x");
    REQUIRE(bad_axis);
    CHECK(bad_axis->find("unknown axis 'colour'") == 0);
    std::string error;
    CHECK_FALSE(parse_variant_key("fresnel", &error));
    CHECK(error == "variant key item 'fresnel': expected axis=choice");
}
