// LDR-FLIP against values derived by hand from the paper's formulas, and its behaviour: zero for
// identical images, growing with the size of a difference, symmetric, finite at the extremes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "watergen/eval/image/flip.h"

using namespace watergen;

namespace {

ImageRGBA8 uniform(uint32_t w, uint32_t h, uint8_t r, uint8_t g, uint8_t b) {
    ImageRGBA8 img{w, h, {}};
    for (std::size_t i = 0; i < img.pixel_count(); ++i)
        img.rgba.insert(img.rgba.end(), {r, g, b, 255});
    return img;
}

void set(ImageRGBA8& img, uint32_t x, uint32_t y, uint8_t r, uint8_t g, uint8_t b) {
    uint8_t* px = &img.rgba[(std::size_t{y} * img.width + x) * 4];
    px[0] = r, px[1] = g, px[2] = b;
}

// A textured image: gradients plus a checkerboard of 3-pixel squares.
ImageRGBA8 textured(uint32_t size, int seed) {
    ImageRGBA8 img = uniform(size, size, 0, 0, 0);
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x)
            set(img, x, y, uint8_t((x * 7 + seed) % 256), uint8_t((y * 5 + 3 * seed) % 256),
                ((x / 3 + y / 3) % 2) ? 230 : 20);
    return img;
}

float max_abs_difference(const FlipMap& a, const FlipMap& b) {
    float m = 0.0f;
    for (std::size_t i = 0; i < a.values.size(); ++i)
        m = std::max(m, std::abs(a.values[i] - b.values[i]));
    return m;
}

} // namespace

TEST_CASE("flip_of_identical_images_is_zero_everywhere", "[unit][flip]") {
    const ImageRGBA8 img = textured(40, 1);
    const FlipMap m = flip_srgb8(img, img);
    REQUIRE(m.ok());
    CHECK(m.width == 40);
    CHECK(m.height == 40);
    REQUIRE(m.values.size() == 1600);
    CHECK(std::all_of(m.values.begin(), m.values.end(), [](float v) { return v == 0.0f; }));
    CHECK(m.mean == 0.0);
    CHECK(m.max == 0.0);
    CHECK(m.p99 == 0.0);
}

TEST_CASE("flip_cmax_is_the_hunt_adjusted_hyab_of_green_and_blue", "[unit][flip]") {
    // Linear green (0, 1, 0): XYZ (0.3576, 0.7152, 0.1192), white (0.9505, 1, 1.0890):
    // L = 116 cbrt(0.7152) - 16 = 87.737, a = -86.188, b = 83.186; Hunt (x 0.87737):
    // a' = -75.619, b' = 72.985. Blue (0, 0, 1): L = 32.303, a = 79.194, b = -107.854; Hunt
    // (x 0.32303): a' = 25.582, b' = -34.840. HyAB = |87.737 - 32.303| +
    // hypot(-75.619 - 25.582, 72.985 + 34.840) = 55.434 + 147.877 = 203.312; ^0.7 = 41.2776.
    CHECK(flip_cmax() == Approx(41.2776).margin(1e-3));
}

TEST_CASE("flip_of_uniform_images_is_the_colour_term_computed_by_hand", "[unit][flip]") {
    // Uniform images: the contrast filters (normalised to sum 1) leave them as they are and the
    // feature detectors (weights summing to 0) see nothing, so FLIP = colour term^1.
    // cmax = 41.2776 (previous test), knee pc cmax = 0.4 * 41.2776 = 16.5110.
    SECTION("grey 128 against 128, 128, 160: one channel, below the knee") {
        // 128 -> linear 0.215861; grey: L = 116 cbrt(0.215861) - 16 = 53.585, a = b = 0.
        // (128, 128, 160): linear (0.215861, 0.215861, 0.351533); XYZ (0.229664, 0.225656,
        // 0.364028); L = 54.622, a = 7.017, b = -17.041; Hunt (x 0.54622): a' = 3.833,
        // b' = -9.308. HyAB = 1.037 + hypot(3.833, 9.308) = 1.037 + 10.066 = 11.1035;
        // ^0.7 = 5.39289 < 16.5110, so 0.95 / 16.5110 * 5.39289 = 0.310292.
        const FlipMap m =
            flip_srgb8(uniform(24, 24, 128, 128, 128), uniform(24, 24, 128, 128, 160));
        REQUIRE(m.ok());
        for (float v : m.values)
            CHECK(v == Approx(0.310292).margin(2e-4));
        CHECK(m.mean == Approx(0.310292).margin(2e-4));
    }
    SECTION("black against red: above the knee") {
        // Red (1, 0, 0): XYZ (0.4124, 0.2126, 0.0193); L = 53.233, a = 80.105, b = 67.223;
        // Hunt (x 0.53233): a' = 42.642, b' = 35.785. Black: L = a = b = 0. HyAB = 53.233 +
        // hypot(42.642, 35.785) = 53.233 + 55.668 = 108.901; ^0.7 = 26.6638 >= 16.5110, so
        // 0.95 + (26.6638 - 16.5110) / (41.2776 - 16.5110) * 0.05 = 0.970497.
        const FlipMap m = flip_srgb8(uniform(24, 24, 0, 0, 0), uniform(24, 24, 255, 0, 0));
        REQUIRE(m.ok());
        for (float v : m.values)
            CHECK(v == Approx(0.970497).margin(2e-4));
    }
}

TEST_CASE("flip_grows_with_the_size_of_a_difference", "[unit][flip]") {
    SECTION("the magnitude of a uniform change") {
        double previous = 0.0;
        for (int step : {10, 40, 80, 155}) {
            const FlipMap m = flip_srgb8(uniform(16, 16, 100, 100, 100),
                                         uniform(16, 16, 100, 100, uint8_t(100 + step)));
            REQUIRE(m.ok());
            INFO("blue + " << step);
            CHECK(m.mean > previous);
            previous = m.mean;
        }
    }
    SECTION("the area of a bright square on grey") {
        const ImageRGBA8 ref = uniform(64, 64, 90, 90, 90);
        double previous = 0.0;
        for (uint32_t side : {1u, 4u, 8u, 16u}) {
            ImageRGBA8 test = ref;
            for (uint32_t y = 24; y < 24 + side; ++y)
                for (uint32_t x = 24; x < 24 + side; ++x)
                    set(test, x, y, 250, 250, 250);
            const FlipMap m = flip_srgb8(ref, test);
            INFO("side " << side);
            CHECK(m.mean > previous);
            previous = m.mean;
        }
    }
}

TEST_CASE("flip_of_a_single_bright_pixel_stays_within_the_kernels_reach", "[unit][flip]") {
    // At 67 ppd the contrast kernels reach ceil(3 sqrt(0.04 / (2 pi^2)) 67) = 10 pixels and the
    // feature kernels ceil(3 * 0.5 * 0.082 * 67) = 9: beyond 10 pixels nothing can differ.
    const ImageRGBA8 ref = uniform(48, 48, 60, 60, 60);
    ImageRGBA8 test = ref;
    set(test, 20, 20, 255, 255, 255);
    const FlipMap m = flip_srgb8(ref, test);
    REQUIRE(m.ok());
    CHECK(m.values[20 * 48 + 20] == Approx(m.max));
    CHECK(m.max > 0.3);
    for (uint32_t y = 0; y < 48; ++y) {
        for (uint32_t x = 0; x < 48; ++x) {
            const uint32_t d = std::max(x > 20 ? x - 20 : 20 - x, y > 20 ? y - 20 : 20 - y);
            if (d > 10) CHECK(m.values[y * 48 + x] == 0.0f);
        }
    }
}

TEST_CASE("flip_is_symmetric_in_its_two_images", "[unit][flip]") {
    // Both terms are absolute differences of per-image quantities (see flip.h).
    const ImageRGBA8 a = textured(32, 1), b = textured(32, 9);
    const FlipMap ab = flip_srgb8(a, b), ba = flip_srgb8(b, a);
    REQUIRE(ab.ok());
    REQUIRE(ba.ok());
    CHECK(ab.mean > 0.05);
    CHECK(max_abs_difference(ab, ba) < 1e-6f);
}

TEST_CASE("flip_is_finite_and_in_range_at_the_black_and_white_extremes", "[unit][flip]") {
    const ImageRGBA8 black = uniform(20, 20, 0, 0, 0), white = uniform(20, 20, 255, 255, 255);
    ImageRGBA8 checker = black, inverse = white;
    for (uint32_t y = 0; y < 20; ++y)
        for (uint32_t x = 0; x < 20; ++x)
            if ((x + y) % 2) set(checker, x, y, 255, 255, 255), set(inverse, x, y, 0, 0, 0);
    for (const auto& [a, b] :
         {std::pair{black, white}, std::pair{white, black}, std::pair{checker, inverse},
          std::pair{black, checker}, std::pair{black, black}, std::pair{white, white}}) {
        const FlipMap m = flip_srgb8(a, b);
        REQUIRE(m.ok());
        CHECK(std::all_of(m.values.begin(), m.values.end(),
                          [](float v) { return std::isfinite(v) && v >= 0.0f && v <= 1.0f; }));
        CHECK(std::isfinite(m.mean));
    }
    // Black against white: HyAB = 100, ^0.7 = 25.1189 above the knee:
    // 0.95 + (25.1189 - 16.5110) / (41.2776 - 16.5110) * 0.05 = 0.967378.
    CHECK(flip_srgb8(black, white).mean == Approx(0.967378).margin(2e-4));
}

TEST_CASE("flip_of_a_fine_pattern_fades_as_the_viewer_steps_back", "[unit][flip]") {
    // A 1-pixel checkerboard against its mean grey: more pixels per degree (a farther viewer)
    // means stronger low-pass filtering, so a smaller difference.
    ImageRGBA8 checker = uniform(32, 32, 64, 64, 64);
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 32; ++x)
            if ((x + y) % 2) set(checker, x, y, 192, 192, 192);
    const ImageRGBA8 grey = uniform(32, 32, 128, 128, 128);
    const FlipMap near = flip_srgb8(checker, grey, 10.0), far = flip_srgb8(checker, grey, 67.0);
    REQUIRE(near.ok());
    REQUIRE(far.ok());
    CHECK(near.mean > far.mean);
}

TEST_CASE("flip_reports_bad_input_as_an_error", "[unit][flip]") {
    CHECK(flip_srgb8(uniform(4, 4, 0, 0, 0), uniform(4, 5, 0, 0, 0)).error ==
          "FLIP: image sizes differ: reference is 4x4, test is 4x5");
    CHECK(flip_srgb8(ImageRGBA8{}, ImageRGBA8{}).error == "FLIP: empty images");
    CHECK_FALSE(flip_srgb8(uniform(4, 4, 0, 0, 0), uniform(4, 4, 0, 0, 0), 0.0).ok());
    ImageRGBA32F nan_image{2, 2, std::vector<float>(16, std::nanf(""))};
    ImageRGBA32F zero{2, 2, std::vector<float>(16, 0.0f)};
    // NaN pixels tone-map to the magenta marker: a large difference, not a NaN.
    const FlipMap m = flip_linear(zero, nan_image);
    REQUIRE(m.ok());
    CHECK(m.mean > 0.9);
}
