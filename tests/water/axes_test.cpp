#include <catch2/catch.hpp>

#include <set>

#include "watergen/plan/covering_array.h"
#include "watergen/water/variant.h"

using namespace watergen;

TEST_CASE("variant_key_round_trips", "[variant]") {
    for (const auto& v : pairwise_covering_variants()) {
        std::string error;
        const auto parsed = parse_variant_key(v.key(), &error);
        REQUIRE(parsed);
        CHECK(parsed->key() == v.key());
    }
}

TEST_CASE("the_space_has_ten_axes_with_every_choice_of_the_seeds", "[variant]") {
    const std::vector<std::pair<std::string, size_t>> expected = {
        {"fresnel", 4}, {"extinction", 5}, {"specular", 4}, {"foam", 4}, {"reflection", 4},
        {"refraction", 3}, {"normals", 4}, {"waves", 5}, {"shore", 2}, {"precision", 2}};
    REQUIRE(axes().size() == expected.size());
    for (size_t i = 0; i < expected.size(); ++i) {
        CHECK(axes()[i].name == expected[i].first);
        CHECK(axes()[i].choices.size() == expected[i].second);
    }
}

TEST_CASE("enumeration_visits_every_valid_variant_once", "[variant]") {
    // 4*5*4*4*4*3*4*5*2*2 = 307200 combinations. Invalid: analytic normals without sines or
    // Gerstner (1 * 3 of the 4*5 normals x waves cells), crest/both foam on flat water
    // (2 * 1 of the 4*5 foam x waves cells), counted once where both apply (1*2*1 of 4*4*5).
    const size_t total = 307200;
    const size_t analytic_bad = total / 20 * 3, crest_bad = total / 20 * 2, both_bad = total / 80 * 2;
    const size_t expected = total - analytic_bad - crest_bad + both_bad;
    CHECK(expected == 238080);
    std::set<std::string> keys;
    size_t visited = 0;
    bool all_valid = true;
    for_each_variant([&](const Variant& v) {
        ++visited;
        keys.insert(v.key());
        all_valid = all_valid && !check_constraints(v);
    });
    CHECK(visited == expected);
    CHECK(keys.size() == expected);
    CHECK(all_valid);
    CHECK(variant_space_size() == expected);
}

TEST_CASE("constraints_name_both_axes", "[variant]") {
    Variant v = default_variant();
    REQUIRE_FALSE(set_choice(v, "normals", "analytic"));
    const auto broken = check_constraints(v);
    REQUIRE(broken);
    CHECK(*broken == "normals=analytic requires waves in {sum_of_sines, gerstner} (analytic normals are the "
                     "derivatives of a closed-form wave model); got waves=flat");
    REQUIRE_FALSE(set_choice(v, "waves", "gerstner"));
    CHECK_FALSE(check_constraints(v));
}

TEST_CASE("covering_set_holds_every_feasible_pair_and_only_valid_variants", "[variant]") {
    const auto set = pairwise_covering_variants();
    CHECK(set.size() < 40); // a few dozen instead of 238080
    std::set<std::string> pairs;
    for (const auto& v : set) {
        CHECK_FALSE(check_constraints(v));
        for (size_t a = 0; a < axes().size(); ++a)
            for (size_t b = a + 1; b < axes().size(); ++b) pairs.insert(axes()[a].name + "=" + v.choices[a] + "," + axes()[b].name + "=" + v.choices[b]);
    }
    size_t feasible = 0;
    for (size_t a = 0; a < axes().size(); ++a)
        for (size_t b = a + 1; b < axes().size(); ++b)
            for (const auto& ca : axes()[a].choices)
                for (const auto& cb : axes()[b].choices) {
                    Variant v = default_variant();
                    v.choices[a] = ca.name;
                    v.choices[b] = cb.name;
                    // Feasible when some valid variant holds it: try every waves choice as the
                    // only axis the constraints depend on.
                    bool ok = false;
                    const size_t w = static_cast<size_t>(find_axis("waves") - axes().data());
                    for (const auto& cw : axes()[w].choices) {
                        Variant t = v;
                        if (w != a && w != b) t.choices[w] = cw.name;
                        ok = ok || !check_constraints(t);
                    }
                    if (!ok) continue;
                    ++feasible;
                    INFO(axes()[a].name << "=" << ca.name << ", " << axes()[b].name << "=" << cb.name);
                    CHECK(pairs.count(axes()[a].name + "=" + ca.name + "," + axes()[b].name + "=" + cb.name) == 1);
                }
    CHECK(pairs.size() == feasible);
    CHECK(pairwise_covering_variants().front().key() == set.front().key()); // deterministic
}

TEST_CASE("unknown_axis_or_choice_names_the_allowed_ones", "[variant]") {
    Variant v = default_variant();
    const auto bad_choice = set_choice(v, "fresnel", "fancy");
    REQUIRE(bad_choice);
    CHECK(*bad_choice == "unknown fresnel choice 'fancy' (choices: none, power, schlick, exact)");
    const auto bad_axis = set_choice(v, "colour", "x");
    REQUIRE(bad_axis);
    CHECK(bad_axis->find("unknown axis 'colour'") == 0);
    std::string error;
    CHECK_FALSE(parse_variant_key("fresnel", &error));
    CHECK(error == "variant key item 'fresnel': expected axis=choice");
}

TEST_CASE("short_hash_is_xxh64_of_the_key", "[variant]") {
    // Pinned: a key's hash never changes, so logs, caches and manifests stay comparable.
    const Variant v = default_variant();
    CHECK(v.key() == "fresnel=schlick,extinction=absorb_scatter,specular=blinn_phong,foam=none,reflection=sky_cubemap,"
                     "refraction=screen_distort,normals=flat,waves=flat,shore=soft,precision=full");
    CHECK(v.short_hash() == "3dc847c87f7a124c");
    Variant other = v;
    REQUIRE_FALSE(set_choice(other, "fresnel", "exact"));
    CHECK(other.short_hash() != v.short_hash());
    CHECK(other.short_hash().size() == 16);
}
