#include <catch2/catch.hpp>

#include <set>

#include "watergen/plan/covering_array.h"
#include "watergen/plan/variant_space.h"
#include "watergen/water/node_catalog.h"
#include "watergen/water/surface.h"
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

namespace {

// The key spelled as a file stem without the cap: '=' -> '-', ',' -> '_'.
std::string uncapped_stem(const Variant& v) {
    std::string s = v.key();
    for (char& c : s)
        c = c == '=' ? '-' : c == ',' ? '_' : c;
    return s;
}

} // namespace

TEST_CASE("a_file_stem_past_the_cap_keeps_a_prefix_and_the_key_hash", "[variant]") {
    // This directory name of the full space spelled out is 258 bytes, past the 255 a file
    // system allows in one name (a build of it failed with "File name too long").
    std::string error;
    const auto longest = parse_variant_key(
        "fresnel=exact,extinction=absorb_scatter,specular=blinn_phong,foam=shore,reflection="
        "fourier_horizon,refraction=screen_distort,normals=heightmap_diff,waves=sum_of_sines,"
        "shore=soft,precision=half,caustics=area_ratio,scene_input=depth_buffer,geometry="
        "tessellated",
        &error);
    REQUIRE(longest);
    const std::string spelled = uncapped_stem(*longest);
    CHECK(spelled.size() == 258);
    const std::string stem = longest->file_stem();
    CHECK(stem.size() == kMaxFileStem);
    CHECK(stem == spelled.substr(0, kMaxFileStem - 17) + "-" + longest->short_hash());
    // A stem within the cap is the key spelled out, as before.
    for (const Variant& v : pairwise_covering_variants())
        if (uncapped_stem(v).size() <= kMaxFileStem) CHECK(v.file_stem() == uncapped_stem(v));
    CHECK(default_variant().file_stem() == uncapped_stem(default_variant()));
}

TEST_CASE("the_axes_keep_the_order_of_a_variant_key", "[variant]") {
    // Pinned: the order of a variant key, hence of every file stem and short hash.
    const std::vector<std::string> expected = {
        "fresnel", "extinction", "specular",  "foam",     "reflection",  "refraction", "normals",
        "waves",   "shore",      "precision", "caustics", "scene_input", "geometry"};
    REQUIRE(axes().size() == expected.size());
    for (size_t i = 0; i < expected.size(); ++i)
        CHECK(axes()[i].name == expected[i]);
}

TEST_CASE("every_choice_of_the_registry_is_consistent", "[variant]") {
    for (const auto& a : axes()) {
        INFO(a.name);
        CHECK(find_choice(a, a.default_choice) != nullptr);
        size_t golds = 0;
        std::set<std::string> names;
        for (const auto& c : a.choices) {
            INFO(c.name);
            CHECK(names.insert(c.name).second);
            CHECK_FALSE(c.description.empty());
            golds += c.gold;
            // A choice approximates another choice of its axis, never itself.
            if (!c.approximates.empty()) {
                CHECK(c.approximates != c.name);
                CHECK(find_choice(a, c.approximates) != nullptr);
            }
            for (const auto& r : c.requirements) {
                const AxisInfo* other = find_axis(r.axis);
                REQUIRE(other != nullptr);
                CHECK(other != &a);
                CHECK_FALSE(r.all_but); // resolved when the registry froze
                CHECK_FALSE(r.choices.empty());
                for (const auto& name : r.choices)
                    CHECK(find_choice(*other, name) != nullptr);
            }
            if (c.node) CHECK(find_catalog_node(a.name + "." + c.name) != nullptr);
        }
        CHECK(golds <= 1);
    }
}

TEST_CASE("every_choice_but_resolves_against_the_other_axis", "[variant]") {
    // foam=crest declares "every waves choice but flat": the list follows the waves axis.
    const ChoiceInfo* crest = find_choice(*find_axis("foam"), "crest");
    REQUIRE(crest);
    REQUIRE(crest->requirements.size() == 1);
    std::vector<std::string> waves;
    for (const auto& c : find_axis("waves")->choices)
        if (c.name != "flat") waves.push_back(c.name);
    CHECK(crest->requirements[0].choices == waves);
}

TEST_CASE("the_catalog_holds_each_choice_node_then_the_axis_extras", "[variant]") {
    size_t expected = 0;
    for (const auto& a : axes()) {
        for (const auto& c : a.choices)
            expected += c.node.has_value();
        expected += a.extra_nodes.size();
    }
    CHECK(node_catalog().size() == expected);
    const CatalogNode* schlick = find_catalog_node("fresnel.schlick");
    REQUIRE(schlick);
    CHECK(schlick->description == "Schlick's approximation, R0 from the indices");
    CHECK(schlick->approximates == "fresnel.exact");
    const CatalogNode* gpugems = find_catalog_node("waves.gerstner.normal_gpugems");
    REQUIRE(gpugems);
    CHECK(gpugems->approximates == "waves.gerstner.normal");
    CHECK(find_catalog_node("specular.none") == nullptr); // no node of its own
}

TEST_CASE("axis_help_lists_every_choice_with_gold_seed_and_what_it_approximates", "[variant]") {
    CHECK(axis_help(*find_axis("fresnel")) ==
          "node on the fresnel axis (default schlick):\n"
          "  none: constant reflectance\n"
          "  power: F = (1 - c)^q, q = 4.5; approximates exact [seed 002]\n"
          "  schlick: Schlick's approximation, R0 from the indices; approximates exact [seed 000]\n"
          "  exact (gold): unpolarised dielectric reflectance with total internal reflection");
}

TEST_CASE("an_unknown_choice_composes_into_a_diagnostic", "[variant]") {
    Graph g;
    Surface s(g);
    compose_choice(s, "fresnel", "fancy");
    REQUIRE(has_errors(g.diagnostics()));
    CHECK(g.diagnostics().front().message == "fresnel: no node for choice 'fancy'");
}

TEST_CASE("registering_after_first_use_is_refused", "[variant]") {
    (void)axes();
    const auto error = register_choice("fresnel", {.name = "late", .description = "too late"});
    REQUIRE(error);
    CHECK(
        *error ==
        "registering fresnel=late: the axis registry is already in use (register before the first "
        "call to axes(), e.g. with WATERGEN_REGISTER_NODES)");
}

TEST_CASE("constraints_name_both_axes", "[variant]") {
    Variant v = default_variant();
    REQUIRE_FALSE(set_choice(v, "normals", "analytic"));
    const auto broken = check_constraints(v);
    REQUIRE(broken);
    CHECK(*broken ==
          "normals=analytic requires waves in {sum_of_sines, gerstner} (analytic normals are the "
          "derivatives of a closed-form wave model); got waves=flat");
    REQUIRE_FALSE(set_choice(v, "waves", "gerstner"));
    CHECK_FALSE(check_constraints(v));
}

TEST_CASE("covering_set_holds_every_feasible_pair_and_only_valid_variants", "[variant]") {
    const auto set = pairwise_covering_variants();
    CHECK(set.size() < 40); // a few dozen instead of the whole space
    std::set<std::string> pairs;
    for (const auto& v : set) {
        CHECK_FALSE(check_constraints(v));
        CHECK(v.choice("geometry") == "screen_pass");
        for (size_t a = 0; a < axes().size(); ++a)
            for (size_t b = a + 1; b < axes().size(); ++b)
                if (axes()[a].name != "geometry" && axes()[b].name != "geometry")
                    pairs.insert(axes()[a].name + "=" + v.choices[a] + "," + axes()[b].name + "=" +
                                 v.choices[b]);
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
                    // The covering set holds geometry at the screen pass (covering_array.cpp).
                    if (!ok || axes()[a].name == "geometry" || axes()[b].name == "geometry")
                        continue;
                    ++feasible;
                    INFO(axes()[a].name << "=" << ca.name << ", " << axes()[b].name << "="
                                        << cb.name);
                    CHECK(pairs.count(axes()[a].name + "=" + ca.name + "," + axes()[b].name + "=" +
                                      cb.name) == 1);
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
    CHECK(v.key() == "fresnel=schlick,extinction=absorb_scatter,specular=blinn_phong,foam=none,"
                     "reflection=sky_cubemap,"
                     "refraction=screen_distort,normals=flat,waves=flat,shore=soft,precision=full,"
                     "caustics=none");
    // xxh64 checked with libxxhash's XXH64(key, 0) outside watergen.
    CHECK(v.short_hash() == "28a40f861046645d");
    Variant other = v;
    REQUIRE_FALSE(set_choice(other, "fresnel", "exact"));
    CHECK(other.short_hash() != v.short_hash());
    CHECK(other.short_hash().size() == 16);
}
