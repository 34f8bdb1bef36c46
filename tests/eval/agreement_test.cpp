#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "watergen/eval/image/agreement.h"

using namespace watergen;

namespace {

ImageRGBA32F grey(uint32_t w, uint32_t h, float v) {
    return {w, h, std::vector<float>(size_t(w) * h * 4, v)};
}

void set_pixel(ImageRGBA32F& img, uint32_t x, uint32_t y, uint32_t c, float v) {
    img.rgba[(size_t(y) * img.width + x) * 4 + c] = v;
}

} // namespace

TEST_CASE("agreement_counts_pixels_over_the_tolerance_and_over_their_bound", "[agreement]") {
    ImageRGBA32F ref = grey(4, 2, 0.5f), test = ref;
    std::vector<float> bound(8, 0.0f);
    set_pixel(test, 1, 0, 0, 0.5f + 1e-4f); // over 5e-5, no bound: unexplained
    set_pixel(test, 2, 1, 2, 0.5f - 3e-4f); // over 5e-5, within 5e-5 + 1e-3
    bound[1 * 4 + 2] = 1e-3f;
    set_pixel(test, 3, 1, 1, 0.5f + 2e-5f); // under the tolerance
    const Agreement a = check_agreement(test, ref, bound, 5e-5);
    CHECK(a.compared == 8);
    CHECK(a.over_tolerance == 2);
    CHECK(a.over_bound == 1);
    CHECK_FALSE(a.holds());
    CHECK(a.worst.x == 1);
    CHECK(a.worst.y == 0);
    CHECK(a.worst_difference == Approx(1e-4).epsilon(1e-3));
    CHECK(a.worst_bound == 0.0);
    CHECK(a.max_bound == Approx(1e-3));

    // With the first pixel's bound raised too, every pixel is explained; the worst is then the
    // largest difference, with its bound.
    bound[1] = 1e-4f;
    const Agreement b = check_agreement(test, ref, bound, 5e-5);
    CHECK(b.holds());
    CHECK(b.over_tolerance == 2);
    CHECK(b.worst.x == 2);
    CHECK(b.worst.y == 1);
    CHECK(b.worst_bound == Approx(1e-3));
}

TEST_CASE("agreement_skips_pixels_not_finite_on_either_side", "[agreement]") {
    ImageRGBA32F ref = grey(2, 1, 0.25f), test = ref;
    set_pixel(test, 0, 0, 1, std::numeric_limits<float>::quiet_NaN());
    set_pixel(ref, 1, 0, 0, std::numeric_limits<float>::infinity());
    const Agreement a = check_agreement(test, ref, {}, 0.0);
    CHECK(a.compared == 0);
    CHECK(a.over_tolerance == 0);
    CHECK(a.holds());
}
