#include <catch2/catch.hpp>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "watergen/plan/variant_list.h"
#include "watergen/plan/variant_space.h"

using namespace watergen;

TEST_CASE("a_variant_list_of_the_full_space_sorts_as_its_keys_do", "[space]") {
    // sort_by_key() compares choice ranks, never a key: the whole space, 3,502,080 variants,
    // must come out in the order of its keys as strings.
    const VariantSpace space = full_space();
    VariantList list(space.choices);
    std::set<std::string> keys;
    enumerate_indices(space, [&](const std::vector<size_t>& index) { list.add(index); });
    enumerate(space, [&](const Variant& v) { keys.insert(v.key()); });
    list.sort_by_key();
    REQUIRE(list.size() == keys.size());
    size_t i = 0, misplaced = 0;
    Variant v = default_variant();
    for (const std::string& key : keys) {
        list.fill(i++, v);
        misplaced += v.key() != key;
    }
    CHECK(misplaced == 0);
}

TEST_CASE("a_variant_list_sorts_a_choice_before_the_longer_ones_it_begins", "[space]") {
    // "x" < "x_y" < "xy" as spelled in a key: "x," < "x_y," < "xy," on an axis followed by
    // another, and "x" < "x_y" < "xy" on the last (no comma after it). Choices written here in
    // another order, on the first and the last axis.
    const std::vector<std::string> tricky{"xy", "x_y", "x"};
    std::vector<std::vector<std::string>> choices(axes().size(), std::vector<std::string>{"c"});
    choices.front() = tricky;
    choices.back() = tricky;
    VariantList list(choices);
    std::set<std::string> keys;
    for (size_t a = 0; a < tricky.size(); ++a)
        for (size_t b = 0; b < tricky.size(); ++b) {
            std::vector<size_t> index(axes().size(), 0);
            index.front() = a;
            index.back() = b;
            list.add(index);
            keys.insert(list.at(list.size() - 1).key());
        }
    list.sort_by_key();
    std::vector<std::string> sorted;
    for (size_t i = 0; i < list.size(); ++i)
        sorted.push_back(list.at(i).key());
    CHECK(sorted == std::vector<std::string>(keys.begin(), keys.end()));
}

TEST_CASE("a_variant_list_gives_its_variants_back_in_their_order", "[space]") {
    std::vector<Variant> variants;
    enumerate(full_space(), [&](const Variant& v) {
        if (variants.size() < 500 && v.key().size() % 7 == 0) variants.push_back(v);
    });
    REQUIRE(variants.size() == 500);
    const VariantSpace space = full_space();
    VariantList list(space.choices);
    for (const Variant& v : variants) {
        std::vector<size_t> index;
        for (size_t a = 0; a < v.choices.size(); ++a)
            index.push_back(
                std::find(space.choices[a].begin(), space.choices[a].end(), v.choices[a]) -
                space.choices[a].begin());
        list.add(index);
    }
    REQUIRE(list.size() == variants.size());
    size_t differ = 0;
    for (size_t i = 0; i < list.size(); ++i)
        differ += list.at(i).key() != variants[i].key();
    CHECK(differ == 0);
    VariantList copy(list.choices());
    copy.add_from(list, 499);
    CHECK(copy.at(0).key() == variants[499].key());
}
