// The timing instrument of `watergen compare`: paired ratios with bootstrap intervals, and the
// runner's interleaved draws (the statistics are asserted, never the times themselves).
#include <catch2/catch.hpp>

#include <cmath>

#include "shared_runner.h"
#include "watergen/eval/draw/variant_render.h"
#include "watergen/eval/measure/interleaved_timing.h"
#include "watergen/pipeline/variant/variant_build.h"

using namespace watergen;

TEST_CASE("a_constant_ratio_has_an_interval_of_zero_width", "[timing]") {
    const std::vector<double> b = {10, 12, 9, 30, 11, 10};
    std::vector<double> a;
    for (double x : b)
        a.push_back(2.0 * x); // the machine's slow round 4 slows both alike
    const RatioInterval r = paired_ratio(a, b);
    CHECK(r.ratio == 2.0);
    CHECK(r.lo == 2.0);
    CHECK(r.hi == 2.0);
    CHECK_FALSE(r.within(0.03));
}

TEST_CASE("the_bootstrap_interval_holds_the_ratio_repeats_and_narrows_with_rounds", "[timing]") {
    // Per-round ratios 1.00, 1.02, 0.98, ... (a fixed pattern of +-2% and +-4%).
    const double pattern[] = {1.00, 1.02, 0.98, 1.04, 0.96, 1.01, 0.99, 1.03};
    auto samples = [&](size_t rounds) {
        std::vector<double> a, b;
        for (size_t k = 0; k < rounds; ++k) {
            b.push_back(10.0 + double(k % 3)); // drift that pairing removes
            a.push_back(b.back() * pattern[k % 8]);
        }
        return std::pair{a, b};
    };
    const auto [a8, b8] = samples(8);
    const RatioInterval r8 = paired_ratio(a8, b8);
    CHECK(r8.ratio == Approx(1.005).epsilon(1e-12)); // median of the 8 ratios: (1.00 + 1.01) / 2
    CHECK(r8.lo <= r8.ratio);
    CHECK(r8.hi >= r8.ratio);
    CHECK(r8.lo >= 0.96);
    CHECK(r8.hi <= 1.04);
    const RatioInterval again = paired_ratio(a8, b8);
    CHECK(again.lo == r8.lo); // seeded: reproducible
    CHECK(again.hi == r8.hi);
    const auto [a64, b64] = samples(64);
    const RatioInterval r64 = paired_ratio(a64, b64);
    CHECK(r64.hi - r64.lo < r8.hi - r8.lo);
    CHECK(r64.within(0.03));
}

TEST_CASE("round_medians_take_the_median_of_each_rounds_draws", "[timing]") {
    CHECK(round_medians({1, 5, 3, 2, 2, 9}, 3) == std::vector<double>{3, 2});
    CHECK(round_medians({4, 6, 1}, 2) == std::vector<double>{5}); // an incomplete round is dropped
    CHECK(paired_ratio({}, {}).ratio == 0);
    CHECK(paired_ratio({1, 2}, {1}).ratio == 0);
}

TEST_CASE("interleaved_draws_give_every_job_its_samples_and_the_image_render_gives", "[timing]") {
    Variant gerstner = default_variant();
    REQUIRE_FALSE(set_choice(gerstner, "waves", "gerstner"));
    const VariantBuild flat = build_variant(default_variant());
    const VariantBuild waves = build_variant(gerstner);
    REQUIRE(flat.ok());
    REQUIRE(waves.ok());
    const SyntheticScene scene = make_synthetic_scene(64, 64);
    const RenderSettings settings{64, 64, 0, false, false};
    const std::vector<RenderJob> jobs = {make_render_job(flat.languages[0], scene, settings),
                                         make_render_job(waves.languages[0], scene, settings)};
    const InterleavedTiming t = time_interleaved(test::shared_runner(), jobs, 4, 3);
    REQUIRE(t.ok());
    REQUIRE(t.results.size() == 2);
    REQUIRE(t.ratios.size() == 2);
    for (size_t i = 0; i < 2; ++i) {
        CHECK(t.results[i].draw_ms.size() == 12); // 4 rounds x 3 draws
        const RenderResult alone = test::shared_runner().render(jobs[i]);
        REQUIRE(alone.ok);
        CHECK(alone.rgba == t.results[i].rgba);
    }
    // Job 0 against its own samples is exactly 1; the A/A copy is a separate pipeline, so its
    // ratio is a measurement (positive, not asserted: wall time on a shared machine).
    CHECK(t.ratios[0].ratio == 1.0);
    CHECK(t.ratios[0].lo == 1.0);
    CHECK(t.aa.ratio > 0);
    CHECK(t.aa.lo <= t.aa.ratio);
    CHECK(t.aa.ratio <= t.aa.hi);
    CHECK(test::shared_runner().validation_messages().empty());
}
