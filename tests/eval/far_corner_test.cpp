#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "shared_runner.h"
#include "watergen/eval/bench/stability_bench.h"
#include "watergen/plan/covering_array.h"

using namespace watergen;

namespace {

// The figures of one variant over a few wave configurations (scenes), per language path: the
// worst continuous max abs, discontinuous count and dE00 p99 over them.
struct Worst {
    std::array<ContinuousError, 2> figure{};
    std::array<double, 2> de00{};
};

Worst worst_over(const VariantBuild& build, const std::vector<SyntheticScene>& scenes,
                 const RenderSettings& settings) {
    Worst w;
    for (const SyntheticScene& scene : scenes) {
        const VariantRender r = render_variant(test::shared_runner(), build, scene, settings);
        REQUIRE(r.ok());
        REQUIRE(r.float_bound.size() == size_t(scene.width) * scene.height);
        for (size_t path = 0; path < 2; ++path) {
            const ImageErrorStats e = compare_images(r.gpu_image[path], r.cpu_double);
            REQUIRE(e.compared_pixels == size_t(scene.width) * scene.height);
            CHECK(e.nan_inf_where_reference_finite == 0);
            const ContinuousError f = continuous_error(r, path);
            w.figure[path].max_abs = std::max(w.figure[path].max_abs, f.max_abs);
            w.figure[path].past_bound = std::max(w.figure[path].past_bound, f.past_bound);
            w.figure[path].discontinuous = std::max(w.figure[path].discontinuous, f.discontinuous);
            w.de00[path] = std::max(w.de00[path], e.ciede2000_p99);
        }
    }
    return w;
}

} // namespace

// The far corner of the stability sweep (bench stability: a week of game time, 100 km from the
// world origin) on every variant of the covering set at 256x256, on lavapipe through both
// language paths, against the CPU evaluator in double over the same moved scene. Conditioned by
// construction (host_values.h: the frame around the eye, phases and scrolls reduced on the
// host), the corner's figures stay within 2x of the same variant's at the origin: the error
// past each continuous pixel's float bound (within 2x, or the renders' tolerance 5e-5), the
// count of discontinuous pixels (within 2x, or 0.1% of the image) and the dE00 p99 over all.
// Before the conditioning the corner was 1.03 from double in sun_glint (15a4795), 1900x its
// origin, and its water pixels' bounds were wide: an unconditioned phase moves by more than a
// radian under a one-ulp move of the time, so it shows in the discontinuous count.
//
// The water at the corner is other water: the waves at x = 100 km a week on are not the waves
// at the origin at time 0, and in grazing views the error of one configuration against another
// varies by up to 20x with no trend in time (measured at 256x256: 1.8e-4 at 0 s, 3.8e-3 at
// 1 h, 7.3e-4 at 1 day, 1.4e-4 at 1 week, all at the origin), in pixels of steep colour whose
// float bound says as much. So the max abs is printed, not held, and each side is the worst of
// two configurations 7 s apart (about a wave period), at the origin from time 0 and at the
// corner from a week. (A third, 13 s, made the test half again as long.)
//
// Open: a depth-buffer scene at the corner has pixels past their float bound by more than 2x
// the origin's (measured worst at 256x256, three configurations: 1.03e-2 against 5.5e-5 in
// grazing, 4.3e-3 against 5.5e-4 in sun_glint, two of the covering set's nine depth-buffer
// variants), where a position texture's stay within it. Until that is found, such a variant is
// held to 0.02 past its bound (the size of a shoreline flip is 0.2).
TEST_CASE("the_covering_set_holds_at_a_week_and_100_km", "[render][stability]") {
    constexpr uint32_t kSize = 256;
    constexpr double kRatio = 2.0, kFlipFloor = kSize * kSize / 1000.0, kWeek = 604800,
                     kDepthBufferPastBound = 0.02;
    RenderSettings settings{kSize, kSize, 1, true};
    settings.float_bound = true;
    for (const char* view : {"sun_glint", "grazing"}) {
        std::vector<SyntheticScene> at_origin, far;
        for (double t : {0.0, 7.0}) {
            at_origin.push_back(stability_scene({"view", view, t, 0, 0}, kSize));
            far.push_back(stability_scene({"view", view, kWeek + t, 1e5, 0}, kSize));
        }
        for (const Variant& v : pairwise_covering_variants()) {
            INFO(v.key() << ", view " << view);
            const VariantBuild build = build_variant(v);
            REQUIRE(build.ok());
            // Flat water without scrolling textures is one configuration at every time.
            const size_t n = v.choice("waves") == "flat" ? 1 : at_origin.size();
            const Worst a = worst_over(build, {at_origin.begin(), at_origin.begin() + n}, settings);
            const Worst b = worst_over(build, {far.begin(), far.begin() + n}, settings);
            for (size_t path = 0; path < 2; ++path) {
                const ContinuousError &fa = a.figure[path], &fb = b.figure[path];
                std::printf("%-60s %-9s %s max abs %.3g -> %.3g, past the bound %.3g -> %.3g, "
                            "discontinuous %zu -> %zu, dE00 p99 %.3g -> %.3g\n",
                            v.key().c_str(), view, path == 0 ? "glsl" : "hlsl", fa.max_abs,
                            fb.max_abs, fa.past_bound, fb.past_bound, fa.discontinuous,
                            fb.discontinuous, a.de00[path], b.de00[path]);
                if (v.choice("scene_input") == "depth_buffer")
                    CHECK(fb.past_bound <= kDepthBufferPastBound);
                else
                    CHECK(stability_within(fb.past_bound, fa.past_bound, kRatio,
                                           kAgreementTolerance));
                CHECK(stability_within(double(fb.discontinuous), double(fa.discontinuous), kRatio,
                                       kFlipFloor));
                CHECK(stability_within(b.de00[path], a.de00[path], kRatio, kStabilityDe00Floor));
            }
        }
    }
}
