#include <catch2/catch.hpp>

#include "build_test_support.h"
#include "shared_runner.h"
#include "watergen/render/prune_measure.h"

using namespace watergen;
using namespace watergen::test;

// The open ocean folds the absorption of 400 m of water and the shore blend away: the pruned
// shader is smaller and draws the same image on lavapipe, through GLSL and HLSL, and on the CPU.
TEST_CASE("pruned_and_unpruned_shaders_draw_the_same_image", "[render]") {
    Diagnostics ds;
    const auto ocean = load_scene(source_dir() + "/examples/scenes/open_ocean.json", ds);
    REQUIRE(ocean);
    const Material m = default_material();
    const auto plan = plan_scene(m, *ocean, ds);
    REQUIRE(plan);
    Variant v = plan->variants.front();
    for (auto [axis, choice] : {std::pair{"fresnel", "schlick"}, std::pair{"specular", "none"},
                                std::pair{"waves", "flat"}, std::pair{"shore", "soft"}})
        REQUIRE_FALSE(set_choice(v, axis, choice));
    const SyntheticScene scene = conform_scene(make_synthetic_scene(64, 64), *plan, m);
    const PruneMeasurement r =
        measure_pruning(shared_runner(), m, *plan, v, scene, RenderSettings{64, 64, 2, false});
    REQUIRE(r.ok());
    CHECK(r.spirv_pruned < r.spirv_unpruned);
    CHECK(r.spirv_opt_pruned < r.spirv_opt_unpruned);
    CHECK(r.live_after < r.live_before);
    CHECK(r.max_abs_glsl <= 1e-4);
    CHECK(r.max_abs_hlsl <= 1e-4);
    CHECK(r.max_abs_cpu <= 1e-4);
}
