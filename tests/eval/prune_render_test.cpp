#include <map>
#include <set>

#include <catch2/catch.hpp>

#include "build_test_support.h"
#include "shared_runner.h"
#include "watergen/eval/bench/prune_bench.h"
#include "watergen/eval/compare/prune_measure.h"

using namespace watergen;
using namespace watergen::test;

namespace {

std::optional<ScenePlan> open_ocean_plan(const Material& m) {
    Diagnostics ds;
    const auto ocean = load_scene(source_dir() + "/examples/scenes/open_ocean.json", ds);
    REQUIRE(ocean);
    auto plan = plan_scene(m, *ocean, ds);
    REQUIRE(plan);
    return plan;
}

} // namespace

// The open ocean folds the absorption of 400 m of water and the shore blend away: the pruned
// shader is smaller and draws the same image on lavapipe, through GLSL and HLSL, and on the CPU.
TEST_CASE("pruned_and_unpruned_shaders_draw_the_same_image", "[render]") {
    const Material m = default_material();
    const std::optional<ScenePlan> plan = open_ocean_plan(m);
    Variant v = plan->variants.front();
    for (auto [axis, choice] : {std::pair{"fresnel", "schlick"}, std::pair{"specular", "none"},
                                std::pair{"waves", "flat"}, std::pair{"shore", "soft"}})
        REQUIRE_FALSE(set_choice(v, axis, choice));
    const SyntheticScene scene = conform_scene(make_synthetic_scene(64, 64), *plan, m);
    const PruneMeasurement r =
        measure_pruning(shared_runner(), m, *plan, v, scene, RenderSettings{64, 64, 2});
    REQUIRE(r.ok());
    CHECK(r.spirv_pruned < r.spirv_unpruned);
    CHECK(r.spirv_opt_pruned < r.spirv_opt_unpruned);
    CHECK(r.live_after < r.live_before);
    CHECK(r.max_abs_glsl <= 1e-4);
    CHECK(r.max_abs_hlsl <= 1e-4);
    CHECK(r.max_abs_cpu <= 1e-4);
}

// bench prune measures a few of a scene's distinct folded shaders: with four, every choice of
// every axis the default material varies that some distinct shader of the scene holds is held
// by a measured one, and the measured shaders are distinct and in plan order.
TEST_CASE("prune_bench_measures_shaders_that_cover_the_scene's_choices", "[render]") {
    const Material m = default_material();
    for (const char* name : {"harbour_night", "mountain_lake", "open_ocean"}) {
        Diagnostics ds;
        const auto scene = load_scene(source_dir() + "/examples/scenes/" + name + ".json", ds);
        REQUIRE(scene);
        const auto plan = plan_scene(m, *scene, ds);
        REQUIRE(plan);
        size_t distinct = 0;
        const std::vector<Variant> all = prune_bench_shaders(m, *plan, 0, &distinct);
        const std::vector<Variant> four = prune_bench_shaders(m, *plan, 4, nullptr);
        INFO(name);
        CHECK(all.size() == distinct);
        CHECK(distinct > 4);
        REQUIRE(four.size() == 4);
        std::set<std::pair<size_t, std::string>> held, measured;
        for (const Variant& v : all)
            for (size_t a = 0; a < v.choices.size(); ++a)
                held.insert({a, v.choices[a]});
        size_t next = 0; // the measured shaders appear in `all` in order
        for (const Variant& v : four) {
            while (next < all.size() && all[next].key() != v.key())
                ++next;
            CHECK(next < all.size());
            for (size_t a = 0; a < v.choices.size(); ++a)
                measured.insert({a, v.choices[a]});
        }
        CHECK(measured == held);
    }
}

// open_ocean skips caustics by its depth (400 m or more; absorb_scatter lets at most 2.1e-9 of
// the sunlight reach the bottom): in the synthetic scene conformed to its facts, the skipped
// Gerstner variant with caustics=area_ratio draws what caustics=none draws, so an engine that
// falls back to none there shows nothing less. Bound 1e-6: the bottom's caustics term is at
// most 2.1e-9 x scene colour (<= 1 here) x the map's range (<= 3.1), plus float rounding of a
// pixel near 0.1 (6e-9); 1e-6 is the agreement bound used for images that must match.
TEST_CASE("caustics_skipped_for_depth_draw_what_no_caustics_draws", "[render]") {
    const Material m = default_material();
    const std::optional<ScenePlan> plan = open_ocean_plan(m);
    Variant none = plan->variants.front();
    REQUIRE_FALSE(set_choice(none, "waves", "gerstner"));
    Variant lit = none;
    REQUIRE_FALSE(set_choice(lit, "caustics", "area_ratio"));
    const ParameterBounds bounds = parameter_bounds(m, plan->fixed);
    REQUIRE(scene_excludes(plan->scene, lit, &bounds));
    REQUIRE_FALSE(scene_excludes(plan->scene, none, &bounds));
    // The caustics map stretched over 40 km, so that every bottom point in view samples it
    // (the default 10 m window would leave the 400 m deep bottom at intensity 1).
    auto everywhere = [](SyntheticScene s) {
        s.uniforms["caustics_window"] = {-2e4, -2e4, 4e4};
        return s;
    };
    const SyntheticScene shallow = everywhere(make_synthetic_scene(256, 256));
    const SyntheticScene deep = everywhere(conform_scene(make_synthetic_scene(256, 256), *plan, m));
    const RenderSettings settings{256, 256, 1, false, false};
    const VariantBuild a = build_shader(m.compose(lit)), b = build_shader(m.compose(none));
    REQUIRE(a.ok());
    REQUIRE(b.ok());
    auto difference = [&](const SyntheticScene& scene, int lang) {
        const VariantRender ra = render_variant(shared_runner(), a, scene, settings);
        const VariantRender rb = render_variant(shared_runner(), b, scene, settings);
        REQUIRE(ra.ok());
        REQUIRE(rb.ok());
        return compare_images(ra.gpu_image[lang], rb.gpu_image[lang]);
    };
    for (int lang = 0; lang < 2; ++lang) {
        const ImageErrorStats d = difference(deep, lang);
        INFO("language " << lang << ": max abs " << d.max_abs);
        CHECK(d.nan_inf_pixels == 0);
        CHECK(d.max_abs <= 1e-6);
    }
    // The same pair in the shallow synthetic scene: the caustics show.
    CHECK(difference(shallow, 0).max_abs > 0.05);
}

TEST_CASE("views_outside_a_scenes_camera_pitch_are_named_with_the_range", "[prune]") {
    // open_ocean's cameras look at most 60 degrees down, harbour_night's 45, mountain_lake's 80:
    // open_water (-65) is outside the first two only, and every other view is inside all three.
    std::map<std::string, std::set<std::string>> outside;
    for (const SceneFacts& s : example_scenes())
        for (const SceneView& v : scene_views())
            if (const std::string why = view_outside_scene(v, s); !why.empty()) {
                outside[s.name].insert(v.name);
                if (s.name == "open_ocean")
                    CHECK(why == "its camera pitch -65 degrees is outside open_ocean's "
                                 "camera_pitch [-60, 10]");
            }
    const std::map<std::string, std::set<std::string>> expected{{"harbour_night", {"open_water"}},
                                                                {"open_ocean", {"open_water"}}};
    CHECK(outside == expected);
}
