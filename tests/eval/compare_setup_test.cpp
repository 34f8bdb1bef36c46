// What `watergen compare` compares, read from its flags before any device is touched
// (compare_setup.h): the product of the axis lists, the keys, the presets as views of their own,
// a scene's views conformed or left out, and every refusal with the flag it names.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "watergen/eval/compare/compare_setup.h"

using namespace watergen;
namespace fs = std::filesystem;

namespace {

// A spec with the given axis lists (axis name -> comma list), 16x16 views, a fresh --out.
CompareSpec spec(const std::map<std::string, std::string>& lists) {
    CompareSpec s;
    s.axis_lists.resize(axes().size());
    for (size_t a = 0; a < axes().size(); ++a)
        if (auto it = lists.find(axes()[a].name); it != lists.end()) s.axis_lists[a] = it->second;
    s.size = 16;
    s.out = (fs::temp_directory_path() / "watergen-compare-setup-test").string();
    return s;
}

std::string example_scene(const std::string& name) {
    const char* src = std::getenv("WATERGEN_SOURCE_DIR");
    REQUIRE(src);
    return std::string(src) + "/examples/scenes/" + name + ".json";
}

std::vector<std::string> view_names(const CompareSetup& s) {
    std::vector<std::string> out;
    for (const auto& [name, scene] : s.views)
        out.push_back(name);
    return out;
}

} // namespace

TEST_CASE("compare_selects_the_product_of_the_axis_lists_then_the_keys", "[compare]") {
    CompareSpec o = spec({{"fresnel", "schlick,exact"}, {"specular", "blinn_phong,ggx_sun"}});
    o.keys = {"foam=shore"};
    o.views = "beach,sun_glint";
    const CompareSetup s = plan_compare(o);
    INFO(s.error);
    REQUIRE(s.status == RunStatus::Ok);
    REQUIRE(s.variants.size() == 5);
    CHECK(s.variants[0].choice("fresnel") == "schlick");
    CHECK(s.variants[0].choice("specular") == "blinn_phong");
    CHECK(s.variants[1].choice("fresnel") == "schlick");
    CHECK(s.variants[1].choice("specular") == "ggx_sun");
    CHECK(s.variants[3].choice("fresnel") == "exact");
    CHECK(s.variants[4].choice("foam") == "shore");
    CHECK(s.variants[4].choice("fresnel") == default_variant().choice("fresnel"));
    CHECK_FALSE(s.reference); // the gold, on the CPU
    CHECK(s.preset == nullptr);
    CHECK(view_names(s) == std::vector<std::string>{"beach", "sun_glint"});
    CHECK(s.views[1].second.width == 16);
    CHECK(s.notes.empty());
}

TEST_CASE("compare_renders_each_view_under_each_preset", "[compare]") {
    CompareSpec o = spec({{"fresnel", "schlick,exact"}});
    o.preset = "tropical_ocean,muddy_river";
    o.views = "beach";
    const CompareSetup s = plan_compare(o);
    REQUIRE(s.status == RunStatus::Ok);
    CHECK(view_names(s) == std::vector<std::string>{"beach@tropical_ocean", "beach@muddy_river"});
    REQUIRE(s.preset);
    CHECK(s.preset->name == "tropical_ocean"); // the variants are built with the first
    CHECK(s.views[1].second.uniforms.at("sun_direction") ==
          find_preset("muddy_river")->values.at("sun_direction"));
}

TEST_CASE("compare_refuses_bad_flags_naming_them", "[compare]") {
    auto refusal = [](const CompareSpec& o) {
        const CompareSetup s = plan_compare(o);
        CHECK(s.status == RunStatus::BadInput);
        return s.error;
    };
    CHECK(refusal(spec({})).rfind("nothing to compare", 0) == 0);
    CHECK(refusal(spec({{"fresnel", "schlick,fancy"}})).rfind("--fresnel: ", 0) == 0);
    CompareSpec key = spec({});
    key.keys = {"fresnel=fancy"};
    CHECK(refusal(key).rfind("--variant 'fresnel=fancy': ", 0) == 0);
    CompareSpec reference = spec({{"fresnel", "schlick,exact"}});
    reference.reference = "colour=red";
    CHECK(refusal(reference).rfind("--reference 'colour=red': ", 0) == 0);
    CompareSpec half = spec({});
    half.scene = example_scene("open_ocean");
    half.strict_half = true;
    CHECK(refusal(half).rfind("--strict-half compares variants named by axis flags", 0) == 0);
    CompareSpec both = spec({{"fresnel", "schlick,exact"}});
    both.scene = example_scene("open_ocean");
    CHECK(refusal(both).rfind("--material / --scene select the variants", 0) == 0);
    // Variants x size^2 bounds what the interleaved timing holds: 16 at 1024 pass, 17 do not.
    CompareSpec big = spec({{"fresnel", "none,power,schlick,exact"},
                            {"specular", "none,toman_glare,blinn_phong,ggx_sun"}});
    big.size = 1024;
    CHECK(plan_compare(big).status != RunStatus::BadInput);
    big.keys = {"foam=shore"};
    CHECK(refusal(big).rfind("--size 1024: 17 variants at 1024x1024 are 17825792 variant pixels "
                             "per view; at most 16777216",
                             0) == 0);
    // A directory that holds anything but an earlier report is not replaced.
    const fs::path foreign = fs::temp_directory_path() / "watergen-compare-setup-foreign";
    fs::create_directories(foreign);
    std::ofstream(foreign / "notes.txt") << "mine";
    CompareSpec out = spec({{"fresnel", "schlick,exact"}});
    out.out = foreign.string();
    CHECK(refusal(out).find("exists and is not an earlier watergen compare report") !=
          std::string::npos);
    fs::remove_all(foreign);
}

TEST_CASE("compare_of_a_scene_leaves_out_the_views_it_never_shows", "[compare]") {
    CompareSpec o = spec({});
    o.scene = example_scene("open_ocean");
    const CompareSetup s = plan_compare(o);
    INFO(s.error);
    REQUIRE(s.status == RunStatus::Ok);
    CHECK(s.from_material);
    REQUIRE(s.plan);
    REQUIRE(s.variants.size() == s.plan->variants.size());
    for (size_t i = 0; i < s.variants.size(); ++i)
        CHECK(s.variants[i].key() == s.plan->variants[i].key());
    // open_water looks 65 degrees down; open_ocean's cameras 60 at most.
    REQUIRE(s.notes.size() == 1);
    CHECK(s.notes[0] == "view open_water left out: its camera pitch -65 degrees is outside "
                        "open_ocean's camera_pitch [-60, 10]");
    CHECK(s.views.size() == scene_views().size() - 1);
    o.views = "open_water";
    const CompareSetup named = plan_compare(o);
    CHECK(named.status == RunStatus::BadInput);
    CHECK(named.error.rfind("--views open_water: its camera pitch -65", 0) == 0);
}

TEST_CASE("a_material_that_does_not_load_stops_with_its_diagnostics", "[compare]") {
    CompareSpec o = spec({});
    o.material = "no_such_material.json";
    const CompareSetup s = plan_compare(o);
    CHECK(s.status == RunStatus::BadInput);
    CHECK(s.error.empty());
    REQUIRE(s.diagnostics.size() == 1);
    CHECK(s.diagnostics[0].message.find("cannot open the file") != std::string::npos);
}

TEST_CASE("compare_past_the_cap_names_the_number_of_variants", "[compare]") {
    // Every choice of the first axes until the product passes the cap, and one key more: the
    // refusal counts them all (it once said "65 variants or more" for any number past 64).
    std::map<std::string, std::string> lists;
    size_t product = 1;
    for (const AxisInfo& axis : axes()) {
        if (product > 2 * kMaxComparedVariants) break;
        std::string list;
        for (const ChoiceInfo& c : axis.choices)
            list += (list.empty() ? "" : ",") + c.name;
        lists[axis.name] = list;
        product *= axis.choices.size();
    }
    REQUIRE(product > 2 * kMaxComparedVariants);
    CompareSpec many = spec(lists);
    many.keys = {"fresnel=schlick"};
    const CompareSetup s = plan_compare(many);
    CHECK(s.status == RunStatus::BadInput);
    CHECK(s.error == std::to_string(product + 1) + " variants to compare; at most " +
                         std::to_string(kMaxComparedVariants));
    // A bad choice past the cap is still named.
    lists["fresnel"] += ",fancy";
    CHECK(plan_compare(spec(lists)).error.rfind("--fresnel: ", 0) == 0);
}
