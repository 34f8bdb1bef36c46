#include <catch2/catch.hpp>

#include <cstdlib>

#include "doc_text.h"
#include "watergen/plan/scene_pruning.h"
#include "watergen/water/scene_quantities.h"

using namespace watergen;

namespace {

std::string example(const std::string& relative) {
    const char* s = std::getenv("WATERGEN_SOURCE_DIR");
    REQUIRE(s != nullptr);
    return std::string(s) + "/examples/" + relative;
}

SceneFacts scene(const std::string& name) {
    Diagnostics ds;
    auto s = load_scene(example("scenes/" + name + ".json"), ds);
    REQUIRE(s);
    return *s;
}

Material full() {
    Diagnostics ds;
    auto m = load_material(example("materials/full.json"), ds);
    REQUIRE(m);
    return *m;
}

Variant with(std::initializer_list<std::pair<const char*, const char*>> choices) {
    Variant v = default_variant();
    for (const auto& [axis, choice] : choices)
        REQUIRE_FALSE(set_choice(v, axis, choice));
    return v;
}

} // namespace

TEST_CASE("scene_facts_rule_out_choices_with_their_reason", "[pruning]") {
    const SceneFacts ocean = scene("open_ocean"), harbour = scene("harbour_night"),
                     lake = scene("mountain_lake");
    auto e = scene_excludes(ocean, with({{"foam", "shore"}}));
    REQUIRE(e);
    CHECK(e->reason == "no shoreline, so shore foam never shows");
    CHECK(e->where.find("open_ocean.json:4:3 /shoreline") != std::string::npos);
    CHECK(scene_excludes(ocean, with({{"foam", "both"}, {"waves", "gerstner"}})));
    CHECK_FALSE(scene_excludes(ocean, with({{"foam", "crest"}, {"waves", "gerstner"}})));
    CHECK_FALSE(scene_excludes(
        harbour,
        with({{"foam", "shore"}, {"reflection", "planar_projective"}, {"specular", "none"}})));

    e = scene_excludes(harbour, with({{"reflection", "sky_cubemap"}}));
    REQUIRE(e);
    CHECK(e->reason == "no cubemap among the scene's reflection sources (planar)");
    CHECK_FALSE(scene_excludes(ocean, with({{"reflection", "sky_cubemap"}})));
    CHECK(scene_excludes(ocean, with({{"reflection", "planar_projective"}})));
    CHECK(scene_excludes(ocean, with({{"reflection", "fourier_horizon"}})));

    e = scene_excludes(harbour, with({{"reflection", "none"}, {"specular", "ggx_sun"}}));
    REQUIRE(e);
    CHECK(e->reason ==
          "the sun never rises (elevation at most -6 degrees), so there is no sun highlight");

    e = scene_excludes(lake, with({{"precision", "full"}}));
    REQUIRE(e);
    CHECK(e->axis == "precision");
    CHECK(e->reason == "the scene targets precision half");

    // An engine that gives only a depth buffer rules out the position texture, and the other
    // way round; a scene that does not say (the examples) keeps both.
    SceneFacts depth_only = ocean;
    depth_only.scene_input = "depth_buffer";
    depth_only.where.fact["scene_input"] = {"engine.json", "/scene_input", {12, 3}};
    e = scene_excludes(depth_only, with({{"scene_input", "position_texture"}}));
    REQUIRE(e);
    CHECK(e->axis == "scene_input");
    CHECK(e->reason == "the engine gives the scene's position as depth_buffer");
    CHECK(e->where.find("engine.json:12:3 /scene_input") != std::string::npos);
    CHECK_FALSE(scene_excludes(depth_only, with({{"scene_input", "depth_buffer"}})));
    CHECK(ocean.scene_input == "any");
    CHECK_FALSE(scene_excludes(ocean, with({{"scene_input", "depth_buffer"}})));
    CHECK_FALSE(scene_excludes(ocean, with({{"scene_input", "position_texture"}})));
}

TEST_CASE("a_sun_below_the_horizon_prunes_every_caustics_choice", "[pruning]") {
    // Caustics are focused sunlight: harbour_night (sun -40..-6 degrees) reaches none of them,
    // whatever the waves; a sunlit scene keeps them.
    const SceneFacts harbour = scene("harbour_night"), ocean = scene("open_ocean");
    for (const char* c : {"texture", "area_ratio", "photon_splat"}) {
        INFO(c);
        const Variant v = with({{"reflection", "planar_projective"},
                                {"specular", "none"},
                                {"waves", "gerstner"},
                                {"caustics", c}});
        auto e = scene_excludes(harbour, v);
        REQUIRE(e);
        CHECK(e->axis == "caustics");
        CHECK(e->reason ==
              "the sun never rises (elevation at most -6 degrees), so there are no caustics");
        CHECK(e->where.find("harbour_night.json") != std::string::npos);
        Variant lit = v;
        REQUIRE_FALSE(set_choice(lit, "reflection", "sky_cubemap"));
        CHECK_FALSE(scene_excludes(ocean, lit));
    }
    CHECK_FALSE(
        scene_excludes(harbour, with({{"reflection", "planar_projective"}, {"specular", "none"}})));
}

namespace {

// open_ocean's facts with the given keys replaced (JSON text of the members), the camera as
// high as `camera_height` says.
SceneFacts ocean_with(const std::string& members,
                      const std::string& camera_height = R"({"min": 4, "max": 40})") {
    const std::string text = R"({"name": "deep", "shoreline": false, "camera_height": )" +
                             camera_height + R"(,
            "camera_pitch": {"min": -60, "max": 10}, "sun_elevation": {"min": 10, "max": 75},
            "reflection_sources": ["cubemap"], "waves": "animated", "precision": "full",
            "platforms": ["vulkan"], )" +
                             members + "}";
    Diagnostic error;
    auto src = JsonSource::parse(text, "deep.json", &error);
    REQUIRE(src);
    Diagnostics ds;
    auto s = parse_scene(*src, ds);
    INFO((ds.empty() ? std::string() : format_diagnostic(ds[0])));
    REQUIRE(s);
    return *s;
}

std::optional<Exclusion> excludes(const Material& m, const SceneFacts& s, const Variant& v) {
    Diagnostics ds;
    const auto plan = plan_scene(m, s, ds);
    INFO((ds.empty() ? std::string() : format_diagnostic(ds[0])));
    REQUIRE(plan);
    const ParameterBounds bounds = parameter_bounds(m, plan->fixed);
    return scene_excludes(s, v, &bounds);
}

} // namespace

TEST_CASE("a_bottom_out_of_view_prunes_every_caustics_choice", "[pruning]") {
    const SceneFacts hidden = ocean_with(R"("water_depth": {"min": 1, "max": 5},
                                            "bottom_in_view": false)");
    const SceneFacts shown = ocean_with(R"("water_depth": {"min": 1, "max": 5})");
    CHECK(shown.bottom_in_view); // the default
    for (const char* c : {"texture", "area_ratio", "photon_splat"}) {
        INFO(c);
        const Variant v = with({{"waves", "gerstner"}, {"caustics", c}});
        auto e = scene_excludes(hidden, v);
        REQUIRE(e);
        CHECK(e->reason == "no bottom in view, so caustics never show");
        CHECK(e->where.find("deep.json:5:") != std::string::npos);
        CHECK_FALSE(scene_excludes(shown, v));
    }
    CHECK_FALSE(scene_excludes(hidden, with({{"waves", "gerstner"}})));
}

TEST_CASE("water_deeper_than_the_sunlight_reaches_prunes_caustics", "[pruning]") {
    // absorb_scatter with absorb_coefficients >= 0.05 / m: exp(-0.05 d) falls below 2^-24 at
    // d = 24 ln 2 / 0.05 = 332.71 m.
    Diagnostics ds;
    const Material m = default_material();
    const Variant v = with({{"waves", "gerstner"}, {"caustics", "area_ratio"}});
    // world_to_meters scales the coefficients: fixed at 1 (it may be 1e-6 otherwise).
    const std::string metres = R"("fixed": {"world_to_meters": 1})";
    auto e = excludes(m, ocean_with(R"("water_depth": {"min": 333, "max": 4000}, )" + metres), v);
    REQUIRE(e);
    CHECK(e->axis == "caustics");
    CHECK(e->reason == "water at least 333 m deep lets at most 5.9e-08 of the sunlight reach the "
                       "bottom (extinction=absorb_scatter, parameters at their most transparent; "
                       "below 2^-24), so there are no caustics");
    CHECK(e->where.find("/water_depth") != std::string::npos);
    CHECK_FALSE(
        excludes(m, ocean_with(R"("water_depth": {"min": 332, "max": 4000}, )" + metres), v));
    CHECK_FALSE(excludes(m, ocean_with(R"("water_depth": {"min": 4000, "max": 4000})"), v));
    // Without the material's ranges the depth rule cannot tell, and keeps the choice.
    CHECK_FALSE(scene_excludes(
        ocean_with(R"("water_depth": {"min": 333, "max": 4000}, "fixed": {"world_to_meters": 1})"),
        v));

    // Each extinction model by its own coefficients: beer_lambert's pure-water absorption may
    // be 0 in blue (the node's range), so light reaches any depth unless a material narrows it.
    Material pure = *MaterialBuilder("pure")
                         .offer("extinction", {"beer_lambert", "linear", "none"})
                         .offer("waves", {"gerstner"})
                         .offer("caustics", {"none", "area_ratio"})
                         .build(ds);
    const SceneFacts deep = ocean_with(R"("water_depth": {"min": 400, "max": 4000})");
    auto model = [](const char* extinction) {
        return with(
            {{"waves", "gerstner"}, {"caustics", "area_ratio"}, {"extinction", extinction}});
    };
    CHECK_FALSE(excludes(pure, deep, model("beer_lambert")));
    CHECK_FALSE(excludes(pure, deep, model("none")));
    CHECK_FALSE(excludes(pure, deep, model("linear"))); // extinction_distances up to 1e6 m
    Material narrow = *MaterialBuilder("narrow")
                           .offer("extinction", {"beer_lambert", "linear"})
                           .offer("waves", {"gerstner"})
                           .offer("caustics", {"none", "area_ratio"})
                           .range("extinction_pure_water_absorption", 0.05, 1.0)
                           .range("extinction_distances", 1.0, 300.0)
                           .build(ds);
    INFO((ds.empty() ? std::string() : format_diagnostic(ds[0])));
    e = excludes(narrow, deep, model("beer_lambert"));
    REQUIRE(e);
    CHECK(e->reason.find("at most 2.1e-09 of the sunlight") != std::string::npos);
    // 000's linear fade is gone at the largest extinction distance (300 m here).
    e = excludes(narrow, deep, model("linear"));
    REQUIRE(e);
    CHECK(e->reason.find("at most 0 of the sunlight") != std::string::npos);
    CHECK_FALSE(excludes(narrow, ocean_with(R"("water_depth": {"min": 299, "max": 4000})"),
                         model("linear")));
}

TEST_CASE("plans_of_the_example_scenes", "[pruning]") {
    const Material m = default_material();
    Diagnostics ds;
    auto ocean = plan_scene(m, scene("open_ocean"), ds);
    REQUIRE(ocean);
    // 400 m and deeper: no sunlight reaches the bottom, so no caustics (16 without them).
    CHECK(ocean->variants.size() == 16);
    CHECK(ocean->skipped == 128);
    CHECK(ocean->fixed.count("water_level"));
    CHECK_FALSE(ocean->fixed.count("time")); // animated waves keep time
    std::vector<std::string> targets;
    for (Target t : ocean->targets)
        targets.push_back(to_string(t));
    CHECK(targets == std::vector<std::string>{"glsl", "hlsl", "spirv", "msl", "reflection"});
    CHECK(ocean->facts.quantity_ranges.at(scene_quantity::water_depth).bounds[0].lo == 400);
    for (size_t i = 1; i < ocean->variants.size(); ++i)
        CHECK(ocean->variants[i - 1].key() < ocean->variants[i].key());

    auto lake = plan_scene(m, scene("mountain_lake"), ds);
    REQUIRE(lake);
    // Half precision, Schlick only (the material's rule), cubemap; caustics with Gerstner only.
    CHECK(lake->variants.size() == 24);
    CHECK(lake->fixed.at("time") == std::vector<double>{0.0});
    for (const Variant& v : lake->variants)
        CHECK((v.choice("fresnel") == "schlick" && v.choice("reflection") == "sky_cubemap"));

    auto harbour = plan_scene(m, scene("harbour_night"), ds);
    REQUIRE(harbour);
    for (const Variant& v : harbour->variants)
        CHECK((v.choice("specular") == "none" && v.choice("reflection") == "planar_projective" &&
               v.choice("caustics") == "none"));
    CHECK(harbour->variants.size() == 16);
    // Night: the sun travels upwards, 0.10..0.64 of its direction.
    const Interval sun_y =
        harbour->facts.quantity_ranges.at(scene_quantity::sun_direction).bounds[1];
    CHECK(sun_y.lo == Approx(0.104528).epsilon(1e-5));
    CHECK(sun_y.hi == Approx(0.642788).epsilon(1e-5));
}

TEST_CASE("the_full_space_per_example_scene", "[pruning]") {
    // What each example scene reaches of the full space (docs/user-guide.md, "Building for
    // scenes"): fractions, since only the axes with scene needs decide them.
    const Material m = full();
    const size_t all = count_variants(full_space());
    REQUIRE(count_variants(m.space) == all);
    Diagnostics ds;
    const auto ocean = plan_scene(m, scene("open_ocean"), ds);
    const auto harbour = plan_scene(m, scene("harbour_night"), ds);
    const auto lake = plan_scene(m, scene("mountain_lake"), ds);
    REQUIRE(ocean);
    REQUIRE(harbour);
    REQUIRE(lake);
    CHECK(ocean->variants.size() * 8 == all);
    // The night reaches caustics=none only (its sun never rises): a 16th of the full space's
    // variants without caustics, counted here.
    size_t without_caustics = 0;
    enumerate(full_space(),
              [&](const Variant& v) { without_caustics += v.choice("caustics") == "none"; });
    CHECK(harbour->variants.size() * 16 == without_caustics);
    for (const Variant& v : harbour->variants)
        REQUIRE(v.choice("caustics") == "none");
    CHECK(lake->variants.size() * 4 == all);
    CHECK(ocean->variants.size() + ocean->skipped == all);
    // The user guide's sentence, as computed (a new choice changes it).
    const std::string sentence =
        "Of the " + std::to_string(all) +
        " variants of the full space (`examples/materials/full.json`), open_ocean reaches " +
        std::to_string(ocean->variants.size()) + ", harbour_night " +
        std::to_string(harbour->variants.size()) + " and mountain_lake " +
        std::to_string(lake->variants.size()) + ";";
    INFO(sentence);
    CHECK(test::user_guide_prose().find(sentence) != std::string::npos);
}

TEST_CASE("scene_parameter_errors_name_the_scene_file", "[pruning]") {
    const Material m = default_material();
    auto check = [&](const std::string& fixed, const std::string& waves,
                     const std::string& expected) {
        const std::string text =
            "{\"name\": \"s\", \"shoreline\": true, \"water_depth\": {\"min\": 0, \"max\": 9},\n"
            "\"camera_height\": {\"min\": 1, \"max\": 9}, \"camera_pitch\": {\"min\": -9, \"max\": "
            "0},\n"
            "\"sun_elevation\": {\"min\": 5, \"max\": 9}, \"reflection_sources\": [], \"waves\": "
            "\"" +
            waves + "\",\n\"precision\": \"any\", \"platforms\": [\"vulkan\"],\n\"fixed\": {" +
            fixed + "}}";
        Diagnostic e;
        const auto src = JsonSource::parse(text, "s.json", &e);
        REQUIRE(src);
        Diagnostics ds;
        const auto s = parse_scene(*src, ds);
        REQUIRE(s);
        CHECK_FALSE(plan_scene(m, *s, ds));
        REQUIRE(ds.size() == 1);
        INFO(format_diagnostic(ds[0]));
        CHECK(format_diagnostic(ds[0]).find(expected) == 0);
    };
    check("\"colour\": 1", "animated",
          "s.json:5:11: error: /fixed/colour: unknown parameter 'colour'; the nodes of material "
          "'default' read ");
    check("\"eye_position\": [1, 2]", "animated",
          "s.json:5:11: error: /fixed/eye_position: parameter 'eye_position' is a vec3: expected 3 "
          "numbers, got 2");
    check("\"shore_hardness\": 9", "animated",
          "s.json:5:11: error: /fixed/shore_hardness: shore_hardness = 9 is out of range; expected "
          "a value in [0.5, 4] 1/m");
    check("\"time\": 3", "animated",
          "s.json:5:11: error: /fixed/time: time is fixed but the scene's waves are animated; "
          "expected \"waves\": \"static\"");
    check("\"sun_direction\": [0, -1, 0]", "animated",
          "s.json:5:11: error: /fixed/sun_direction: the fixed sun direction has elevation 90 "
          "degrees; expected one within "
          "sun_elevation [5, 9]");
    // A fixed value must obey the scene's own ranges, not only the parameter's: an eye 50 km
    // below the water with a camera 1..9 m above it, a zero sun direction (which would fold
    // every sun term away), and bounds printed exactly (4.0000001 is not "4").
    check("\"water_level\": 0, \"eye_position\": [0, -50000, 0]", "animated",
          "s.json:5:29: error: /fixed/eye_position: the fixed eye position is -50000 m above the "
          "water (eye y -50000, "
          "water level 0..0 m); expected a height within camera_height [1, 9] m");
    check(
        "\"water_level\": 2, \"eye_position\": [0, 12, 0]", "animated",
        "s.json:5:29: error: /fixed/eye_position: the fixed eye position is 10 m above the water");
    check("\"sun_direction\": [0, 0, 0]", "animated",
          "s.json:5:11: error: /fixed/sun_direction: the fixed sun direction (0, 0, 0) has length "
          "0; expected a direction");
    check("\"shore_hardness\": 4.0000001", "animated",
          "s.json:5:11: error: /fixed/shore_hardness: shore_hardness = 4.0000001 is out of range; "
          "expected a value in "
          "[0.5, 4] 1/m");
}

TEST_CASE("a_fixed_eye_within_the_camera_height_plans", "[pruning]") {
    const std::string text =
        "{\"name\": \"s\", \"shoreline\": true, \"water_depth\": {\"min\": 0, \"max\": 9},\n"
        "\"camera_height\": {\"min\": 1, \"max\": 9}, \"camera_pitch\": {\"min\": -9, \"max\": "
        "0},\n"
        "\"sun_elevation\": {\"min\": 5, \"max\": 9}, \"reflection_sources\": [\"cubemap\"], "
        "\"waves\": \"animated\",\n"
        "\"precision\": \"any\", \"platforms\": [\"vulkan\"],\n"
        "\"fixed\": {\"water_level\": 2, \"eye_position\": [0, 7, -3]}}";
    Diagnostic e;
    const auto src = JsonSource::parse(text, "s.json", &e);
    REQUIRE(src);
    Diagnostics ds;
    const auto s = parse_scene(*src, ds);
    REQUIRE(s);
    const auto plan = plan_scene(default_material(), *s, ds);
    std::string errors;
    for (const auto& d : ds)
        errors += format_diagnostic(d) + "\n";
    INFO(errors);
    REQUIRE(plan);
    CHECK(plan->fixed.at("eye_position") == std::vector<double>{0, 7, -3});
}

TEST_CASE("a_camera_that_never_comes_near_the_water_prunes_tessellation", "[pruning]") {
    // An edge's factor is tess_scale / its distance from the eye, at least the camera's height
    // above the water: from at least tess_scale's largest value up, every factor is 1.
    Diagnostics ds;
    const Material m = *MaterialBuilder("geometry")
                            .offer("waves", {"gerstner"})
                            .offer("geometry", {"screen_pass", "mesh", "tessellated"})
                            .range("tess_scale", 1.0, 30.0)
                            .build(ds);
    INFO((ds.empty() ? std::string() : format_diagnostic(ds[0])));
    auto high = [](double lowest) {
        return ocean_with(R"("water_depth": {"min": 1, "max": 50})",
                          R"({"min": )" + std::to_string(lowest) + R"(, "max": 400})");
    };
    const Variant tess = with({{"waves", "gerstner"}, {"geometry", "tessellated"}});
    auto e = excludes(m, high(50), tess);
    REQUIRE(e);
    CHECK(e->axis == "geometry");
    CHECK(e->reason == "the camera stays at least 50 m above the water and tess_scale is at most "
                       "30 m, so every tessellation factor is 1, so the mesh geometry draws the "
                       "same");
    CHECK(e->where.find("deep.json") != std::string::npos);
    CHECK(e->where.find("/camera_height") != std::string::npos);
    CHECK_FALSE(excludes(m, high(20), tess));
    CHECK_FALSE(excludes(m, high(50), with({{"waves", "gerstner"}, {"geometry", "mesh"}})));
}
