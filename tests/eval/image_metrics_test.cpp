// compare_images, tone mapping and is_degenerate on small hand-made images.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "watergen/eval/image/image_metrics.h"

using namespace watergen;

namespace {

// A w x h image whose values are multiples of 1/64 (exact in float, so differences are exact).
ImageRGBA32F gradient(uint32_t w, uint32_t h) {
    ImageRGBA32F img{w, h, std::vector<float>(std::size_t{w} * h * 4)};
    for (std::size_t i = 0; i < img.rgba.size(); ++i) {
        img.rgba[i] = (i % 4 == 3) ? 1.0f : static_cast<float>((i * 7) % 49) / 64.0f;
    }
    return img;
}

float& at(ImageRGBA32F& img, uint32_t x, uint32_t y, int c) {
    return img.rgba[(std::size_t{y} * img.width + x) * 4 + c];
}

std::vector<uint8_t> tone_map_one(float v, float exposure = 1.0f) {
    return tone_map_to_srgb8(ImageRGBA32F{1, 1, {v, v, v, 0.5f}}, exposure);
}

} // namespace

TEST_CASE("identical images have zero error, infinite PSNR and zero CIEDE2000", "[unit][metrics]") {
    const ImageRGBA32F img = gradient(5, 4);
    const ImageErrorStats s = compare_images(img, img);
    REQUIRE(s.ok());
    CHECK(s.pixel_count == 20);
    CHECK(s.compared_pixels == 20);
    CHECK(s.nan_inf_pixels == 0);
    CHECK(s.max_abs == 0.0);
    CHECK(s.rmse == 0.0);
    CHECK(std::isinf(s.psnr_db));
    CHECK(s.psnr_db > 0);
    CHECK(s.ciede2000_mean == 0.0);
    CHECK(s.ciede2000_p99 == 0.0);
}

TEST_CASE("one channel of one pixel off by 0.25 gives exact max_abs, rmse and psnr",
          "[unit][metrics]") {
    const uint32_t w = 4, h = 3;
    const ImageRGBA32F ref = gradient(w, h);
    ImageRGBA32F test = ref;
    at(test, 2, 1, 1) += 0.25f;

    const ImageErrorStats s = compare_images(test, ref);
    REQUIRE(s.ok());
    const double n = w * h;
    const double rmse = std::sqrt(0.25 * 0.25 / (3.0 * n));
    CHECK(s.max_abs == 0.25);
    CHECK(s.max_abs_location.x == 2);
    CHECK(s.max_abs_location.y == 1);
    CHECK(s.rmse == Approx(rmse).epsilon(1e-12));
    CHECK(s.psnr_db == Approx(10.0 * std::log10(1.0 / (rmse * rmse))).epsilon(1e-12));

    // Only that pixel differs: mean = its dE / N; p99 (nearest rank of 12 values) = the max.
    const auto t8 = tone_map_to_srgb8(test);
    const auto r8 = tone_map_to_srgb8(ref);
    const std::size_t i = (1 * w + 2) * 4;
    const double de = ciede2000(srgb8_to_lab(t8[i], t8[i + 1], t8[i + 2]),
                                srgb8_to_lab(r8[i], r8[i + 1], r8[i + 2]));
    REQUIRE(de > 1.0);
    CHECK(s.ciede2000_p99 == Approx(de).epsilon(1e-12));
    CHECK(s.ciede2000_mean == Approx(de / n).epsilon(1e-12));
}

TEST_CASE("a NaN pixel in the test image is counted and excluded from the error figures",
          "[unit][metrics]") {
    const ImageRGBA32F ref = gradient(4, 4);
    ImageRGBA32F test = ref;
    at(test, 1, 3, 0) = std::numeric_limits<float>::quiet_NaN();
    at(test, 3, 0, 2) = std::numeric_limits<float>::infinity();
    at(test, 0, 2, 2) += 0.125f;

    const ImageErrorStats s = compare_images(test, ref);
    REQUIRE(s.ok());
    CHECK(s.nan_inf_pixels == 2);
    CHECK(s.reference_nan_inf_pixels == 0);
    CHECK(s.compared_pixels == 14);
    CHECK(s.max_abs == 0.125);
    CHECK(s.max_abs_location.x == 0);
    CHECK(s.max_abs_location.y == 2);
    CHECK(s.rmse == Approx(std::sqrt(0.125 * 0.125 / (3.0 * 14))).epsilon(1e-12));
    CHECK(std::isfinite(s.ciede2000_mean));
    CHECK(s.nan_inf_where_reference_finite == 2);
}

TEST_CASE("non_finite_pixels_of_both_sides_are_not_counted_as_the_test_side_breaking",
          "[unit][metrics]") {
    ImageRGBA32F ref = gradient(4, 4);
    ImageRGBA32F test = ref;
    at(test, 1, 3, 0) = std::numeric_limits<float>::quiet_NaN(); // test only
    at(test, 2, 2, 1) = std::numeric_limits<float>::infinity();  // both
    at(ref, 2, 2, 0) = std::numeric_limits<float>::quiet_NaN();
    at(ref, 0, 0, 0) = std::numeric_limits<float>::infinity(); // reference only
    const ImageErrorStats s = compare_images(test, ref);
    REQUIRE(s.ok());
    CHECK(s.nan_inf_pixels == 2);
    CHECK(s.reference_nan_inf_pixels == 2);
    CHECK(s.nan_inf_where_reference_finite == 1);
    CHECK(s.compared_pixels == 13);
}

TEST_CASE("an all-NaN test image yields NaN error figures so thresholds fail", "[unit][metrics]") {
    const ImageRGBA32F ref = gradient(2, 2);
    ImageRGBA32F test = ref;
    for (float& v : test.rgba)
        v = std::numeric_limits<float>::quiet_NaN();
    const ImageErrorStats s = compare_images(test, ref);
    REQUIRE(s.ok());
    CHECK(s.nan_inf_pixels == 4);
    CHECK(s.compared_pixels == 0);
    CHECK_FALSE(s.psnr_db > 0.0);
    CHECK_FALSE(s.max_abs < 1.0);
    CHECK_FALSE(s.ciede2000_mean < 1.0);
}

TEST_CASE("images of different sizes, empty or malformed images are an error", "[unit][metrics]") {
    const ImageErrorStats s = compare_images(gradient(4, 3), gradient(3, 4));
    CHECK_FALSE(s.ok());
    CHECK(s.error.find("4x3") != std::string::npos);
    CHECK(s.error.find("3x4") != std::string::npos);
    CHECK(s.pixel_count == 0);

    CHECK_FALSE(compare_images(ImageRGBA32F{}, ImageRGBA32F{}).ok());
    ImageRGBA32F short_data = gradient(2, 2);
    short_data.rgba.pop_back();
    CHECK_FALSE(compare_images(short_data, gradient(2, 2)).ok());
    CHECK_FALSE(compare_images(gradient(2, 2), short_data).ok());
}

TEST_CASE("exposure scales values before the perceptual comparison only", "[unit][metrics]") {
    ImageRGBA32F ref{1, 1, {0.25f, 0.25f, 0.25f, 1.0f}};
    ImageRGBA32F test{1, 1, {0.5f, 0.5f, 0.5f, 1.0f}};
    // Exposure 8 pushes both to >= 1, which clips to the same white.
    const ImageErrorStats s = compare_images(test, ref, 8.0f);
    REQUIRE(s.ok());
    CHECK(s.max_abs == 0.25);
    CHECK(s.ciede2000_mean == 0.0);
    CHECK(compare_images(test, ref, 1.0f).ciede2000_mean > 1.0);
}

TEST_CASE("tone_map_to_srgb8 applies the exact sRGB curve at known values", "[unit][srgb]") {
    CHECK(tone_map_one(0.0f) == std::vector<uint8_t>{0, 0, 0, 255});
    CHECK(tone_map_one(1.0f) == std::vector<uint8_t>{255, 255, 255, 255});
    CHECK(tone_map_one(0.5f) == std::vector<uint8_t>{188, 188, 188, 255}); // 0.7354 * 255
    // Linear segment boundary: 12.92 * 0.0031308 = 0.04045 -> 10.31 -> 10 on both sides.
    CHECK(tone_map_one(0.0031308f)[0] == 10);
    CHECK(tone_map_one(0.0031307f)[0] == 10);
    CHECK(tone_map_one(0.0031309f)[0] == 10);
    CHECK(tone_map_one(0.001f)[0] == 3);    // 12.92 * 0.001 * 255 = 3.29 (linear segment)
    CHECK(tone_map_one(0.2159f)[0] == 128); // code 128 decodes to 0.21586 linear
    // Clamping, and exposure applied before it.
    CHECK(tone_map_one(-3.0f)[0] == 0);
    CHECK(tone_map_one(7.5f)[0] == 255);
    CHECK(tone_map_one(0.25f, 2.0f)[0] == 188);
}

TEST_CASE("sRGB encode is the piecewise IEC 61966-2-1 curve and decode inverts it",
          "[unit][srgb]") {
    CHECK(linear_to_srgb(0.0031308) == 12.92 * 0.0031308);
    CHECK(linear_to_srgb(std::nextafter(0.0031308, 1.0)) == Approx(12.92 * 0.0031308).margin(1e-6));
    CHECK(linear_to_srgb(1.0) == Approx(1.0).margin(1e-15));
    CHECK(linear_to_srgb(0.5) == Approx(0.735357).margin(1e-6));
    for (double v : {0.0, 0.001, 0.0031308, 0.01, 0.18, 0.5, 0.9, 1.0}) {
        INFO(v);
        CHECK(srgb_to_linear(linear_to_srgb(v)) == Approx(v).margin(1e-12));
    }
}

TEST_CASE("tone_map_to_srgb8 marks NaN and Inf pixels magenta", "[unit][srgb]") {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const ImageRGBA32F img{
        3, 1, {0.5f, nan, 0.5f, 1.0f, inf, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, nan}};
    const std::vector<uint8_t> expected{255, 0, 255, 255, 255, 0, 255, 255, 0, 0, 0, 255};
    CHECK(tone_map_to_srgb8(img) == expected);
    // Malformed input gives an empty result rather than reading out of bounds.
    CHECK(tone_map_to_srgb8(ImageRGBA32F{2, 2, {0.0f}}).empty());
}

TEST_CASE("is_degenerate is true for empty, constant and all-zero images only", "[unit][metrics]") {
    CHECK(is_degenerate(ImageRGBA32F{}));
    CHECK(is_degenerate(ImageRGBA32F{2, 1, std::vector<float>(8, 0.0f)}));
    CHECK(is_degenerate(ImageRGBA32F{2, 1, {0.3f, 0.2f, 0.1f, 1.0f, 0.3f, 0.2f, 0.1f, 0.0f}}));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    CHECK(is_degenerate(ImageRGBA32F{2, 1, std::vector<float>(8, nan)}));
    CHECK_FALSE(is_degenerate(gradient(3, 3)));
    ImageRGBA32F one_pixel_differs{2, 1, std::vector<float>(8, 0.0f)};
    one_pixel_differs.rgba[6] = 1e-6f;
    CHECK_FALSE(is_degenerate(one_pixel_differs));
}

TEST_CASE("nearest_rank_percentile picks sorted[ceil(p n / 100) - 1]", "[unit][metrics]") {
    std::vector<double> hundred;
    for (int i = 100; i >= 1; --i)
        hundred.push_back(i);
    CHECK(nearest_rank_percentile(hundred, 99) == 99.0);
    CHECK(nearest_rank_percentile(hundred, 50) == 50.0);
    CHECK(nearest_rank_percentile(hundred, 100) == 100.0);
    CHECK(nearest_rank_percentile(hundred, 1) == 1.0);
    // n = 3: the 99th percentile is rank ceil(2.97) = 3, the median rank ceil(1.5) = 2.
    std::vector<double> three{5.0, 1.0, 3.0};
    CHECK(nearest_rank_percentile(three, 99) == 5.0);
    CHECK(nearest_rank_percentile(three, 50) == 3.0);
    std::vector<double> none;
    CHECK(std::isnan(nearest_rank_percentile(none, 50)));
}

TEST_CASE("linear_srgb_to_lab maps greys to a = b = 0 and is what srgb8_to_lab decodes into",
          "[unit][metrics]") {
    // Linear 0.18 grey: L = 116 cbrt(0.18) - 16 = 49.4961.
    const Lab grey = linear_srgb_to_lab(0.18, 0.18, 0.18);
    CHECK(grey.L == Approx(49.4961).margin(1e-4));
    CHECK(grey.a == Approx(0.0).margin(1e-12));
    // The 8-bit path is decoding followed by the linear one.
    const Lab red8 = srgb8_to_lab(255, 0, 0);
    const Lab red = linear_srgb_to_lab(1.0, 0.0, 0.0);
    CHECK(red8.L == red.L);
    CHECK(red8.a == red.a);
    CHECK(red8.b == red.b);
    const XYZ w = srgb_white_xyz();
    CHECK(w.X == Approx(0.9505));
    CHECK(w.Z == Approx(1.089));
}
