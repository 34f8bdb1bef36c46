// compare with the CPU reference (compare_run.h): each entry's pixels beyond what float rounding
// explains. The gold variant's own GPU render is the same model as the reference, so every
// pixel is within the allowance; Schlick's approximation differs from the exact Fresnel as a
// model, so many are not.
#include <catch2/catch.hpp>

#include "shared_runner.h"
#include "watergen/eval/compare/compare_run.h"

using namespace watergen;

TEST_CASE("compare_counts_the_pixels_float_rounding_does_not_explain", "[render][compare]") {
    std::vector<Variant> variants(2, default_variant());
    REQUIRE_FALSE(set_choice(variants[0], "fresnel", "exact"));
    REQUIRE_FALSE(set_choice(variants[1], "fresnel", "schlick"));
    CompareRequest request;
    request.variants = variants;
    request.views = {{"beach", make_synthetic_scene(64, 64)}};
    request.rounds = 3;
    request.draws = 1;
    const CompareRun run = run_compare(test::shared_runner(), request);
    INFO(run.error);
    REQUIRE(run.ok());
    REQUIRE(run.reference_on_cpu);
    REQUIRE(run.entries.size() == 2);
    for (const CompareEntry& e : run.entries) {
        INFO(e.variant.key());
        REQUIRE(e.views.size() == 1);
        const ComparedView& v = e.views[0];
        CHECK(v.float_bound_max > 0);
        CHECK(v.float_bound_max < 1e-3); // the beach view at 64x64: measured 7.2e-6
        if (e.variant.choice("fresnel") == "exact") {
            CHECK(v.beyond_float_bound == 0);
        } else {
            // Measured: 3,904 of 4,096 pixels (Schlick is off the exact reflectance over the
            // water by far more than float rounding).
            CHECK(v.beyond_float_bound > 2000);
        }
    }
}
