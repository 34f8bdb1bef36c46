// The covering set's half variants rendered in 16-bit arithmetic on lavapipe at 256x256 (the
// size users render previews at; run_half_bench): no NaN/Inf pixel, the GLSL image agrees with
// the CPU half model to the bit almost everywhere, and the error against full precision that
// the CPU emulation predicts is the error the GPU shows.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "shared_runner.h"
#include "watergen/eval/bench/half_bench.h"
#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/plan/covering_array.h"

using namespace watergen;

TEST_CASE("strict_half_covering_variants_at_256_agree_with_the_cpu_half_model", "[render][half]") {
    const HalfBench bench = run_half_bench(test::shared_runner(), 256, 1);
    INFO(bench.error);
    REQUIRE(bench.ok());
    REQUIRE(bench.rows.size() >= 8);
    // half.csv: the header and a line per variant; half.json: a row per variant.
    CHECK(size_t(std::count(bench.csv.begin(), bench.csv.end(), '\n')) == bench.rows.size() + 1);
    CHECK(bench.csv.rfind("variant,glsl_equal_pct,", 0) == 0);
    CHECK(nlohmann::json::parse(bench.json).at("rows").size() == bench.rows.size());
    for (const HalfBenchRow& r : bench.rows) {
        INFO(r.key);
        for (int i = 0; i < 2; ++i) {
            CHECK(r.vs_full[i].nan_inf_pixels == 0);
            CHECK(r.vs_full[i].compared_pixels == 256u * 256u);
        }
        // GLSL: every operation is the model's but for exp of products and atan2
        // (strict_half_node_test), and a texel near a rounding boundary can round the other
        // way (lavapipe filters in 32 bits, the CPU in double); measured 98.90% of channels
        // within 1 ulp at worst (the beer_lambert variant), 99.9% typical.
        const HalfAgreement& g = r.vs_cpu_half[0];
        REQUIRE(g.values == 3u * 256u * 256u);
        CHECK(static_cast<double>(g.within_1) >= 0.98 * static_cast<double>(g.values));
        // What the CPU emulation says half precision costs is what the GPU's half costs: the
        // p99 colour differences against full precision agree within 0.05 dE00 (measured
        // 0.0007 at most), the largest linear error within 4e-3 (one binary16 step at 8).
        CHECK(std::fabs(r.vs_full[0].ciede2000_p99 - r.cpu_half_vs_full.ciede2000_p99) <= 0.05);
        CHECK(std::fabs(r.vs_full[0].max_abs - r.cpu_half_vs_full.max_abs) <= 4e-3);
    }
}

namespace {

size_t non_finite_pixels(const ImageRGBA32F& image) {
    size_t n = 0;
    for (size_t p = 0; p < image.rgba.size() / 4; ++p)
        n += !std::isfinite(image.rgba[p * 4]) || !std::isfinite(image.rgba[p * 4 + 1]) ||
             !std::isfinite(image.rgba[p * 4 + 2]);
    return n;
}

} // namespace

TEST_CASE("a_nan_and_an_inf_texel_spread_no_further_in_strict_half_than_in_float",
          "[render][half][stress]") {
    // water-models.md: one NaN or +inf texel in each input texture must stay contained. Every
    // texture of the synthetic scene gets a NaN texel and a +inf texel; each half variant of
    // the covering set is rendered in 16-bit arithmetic and through its 32-bit (mediump) build.
    // A texel seen by many pixels (a sky cube texel, a scene texel under refraction) poisons
    // them in 32 bits too (up to 145 of 16384 pixels, measured). In 16 bits a texture
    // coordinate computed in half moves a lookup by up to 2^-11 (1/16 texel of a 128-texel
    // map), so a poisoned footprint may gain a pixel at its edge (the CPU half model shows the
    // same pixel poisoned: the planar reflection map's lookup moved onto the texel); measured:
    // at most 2 more.
    const RenderSettings settings{128, 128, 0, false, false};
    SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    for (auto& [name, t] : scene.textures) {
        const size_t texels = size_t(t.width) * t.height * t.layers;
        for (int c = 0; c < 3; ++c) {
            t.rgba[(texels / 3) * 4 + c] = NAN;
            t.rgba[(2 * texels / 3 + 5) * 4 + c] = INFINITY;
        }
    }
    for (const Variant& v : pairwise_covering_variants()) {
        if (v.choice("precision") != "half") continue;
        INFO(v.key());
        size_t count[2] = {0, 0};
        for (bool strict : {false, true}) {
            const VariantBuild build = build_variant(v, nullptr, EmitOptions{strict});
            REQUIRE(build.ok());
            const VariantRender r = render_variant(test::shared_runner(), build, scene, settings);
            INFO(r.error);
            REQUIRE(r.ok());
            // The worse of the two paths (HLSL's 16-bit intrinsics run at 32 bits).
            count[strict] =
                std::max(non_finite_pixels(r.gpu_image[0]), non_finite_pixels(r.gpu_image[1]));
        }
        std::printf("non-finite pixels of 16384: 32-bit %zu, 16-bit %zu  %s\n", count[0], count[1],
                    v.key().c_str());
        CHECK(count[1] <= count[0] + 4);
        CHECK(count[0] <= 200); // about one per cent: a few neighbourhoods, not the image
    }
}
