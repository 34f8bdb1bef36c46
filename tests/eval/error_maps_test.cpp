// Error maps, heat maps and where to look, on hand-made images.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "watergen/eval/image/error_maps.h"
#include "watergen/eval/image/heat_map.h"

using namespace watergen;

namespace {

ImageRGBA32F grey(uint32_t w, uint32_t h, float v) {
    ImageRGBA32F img{w, h, std::vector<float>(std::size_t{w} * h * 4, v)};
    return img;
}

void set_rgb(ImageRGBA32F& img, uint32_t x, uint32_t y, float v) {
    for (int c = 0; c < 3; ++c)
        img.rgba[(std::size_t{y} * img.width + x) * 4 + c] = v;
}

std::array<uint8_t, 3> pixel(const ImageRGBA8& img, uint32_t x, uint32_t y) {
    const uint8_t* p = &img.rgba[(std::size_t{y} * img.width + x) * 4];
    return {p[0], p[1], p[2]};
}

bool contains(PixelRegion r, uint32_t x, uint32_t y) {
    return x >= r.x && x < r.x + r.width && y >= r.y && y < r.y + r.height;
}

} // namespace

TEST_CASE("the_worst_region_contains_a_single_bright_blob", "[unit][error_maps]") {
    const ImageRGBA32F ref = grey(96, 64, 0.2f);
    ImageRGBA32F test = ref;
    for (uint32_t y = 40; y < 44; ++y)
        for (uint32_t x = 70; x < 74; ++x)
            set_rgb(test, x, y, 1.0f);
    const ErrorMaps m = compute_error_maps(test, ref);
    REQUIRE(m.ok());
    CHECK(default_window_size(96, 64) == 8);
    CHECK(m.worst.width == 8);
    CHECK(m.worst.height == 8);
    for (uint32_t y = 40; y < 44; ++y)
        for (uint32_t x = 70; x < 74; ++x)
            CHECK(contains(m.worst, x, y));
    // 16 of 6144 pixels differ, each far beyond a just noticeable difference.
    CHECK(m.share_above_jnd == Approx(16.0 / 6144.0));
    CHECK(m.stats.nan_inf_pixels == 0);
    CHECK(m.flip.ok());
    CHECK(m.flip.values[41 * 96 + 71] > 0.5f);
    CHECK(m.flip.values[5 * 96 + 5] == 0.0f);
}

TEST_CASE("the_ciede2000_map_agrees_with_compare_images", "[unit][error_maps]") {
    ImageRGBA32F ref = grey(16, 16, 0.3f), test = ref;
    for (uint32_t i = 0; i < 16; ++i)
        set_rgb(test, i, i, 0.3f + 0.04f * float(i));
    set_rgb(test, 5, 9, std::numeric_limits<float>::quiet_NaN());
    const ErrorMaps m = compute_error_maps(test, ref);
    REQUIRE(m.ok());
    REQUIRE(m.ciede2000.size() == 256);
    CHECK(std::isnan(m.ciede2000[9 * 16 + 5]));
    CHECK(m.stats.nan_inf_pixels == 1);
    double sum = 0.0;
    for (float v : m.ciede2000)
        if (std::isfinite(v)) sum += v;
    CHECK(sum / 255.0 == Approx(m.stats.ciede2000_mean).epsilon(1e-6));
    CHECK(m.ciede2000[0] == 0.0f);
    CHECK(m.ciede2000[15 * 16 + 15] > 10.0f);
    // The NaN pixel weighs as dE 100 and draws the 2x2 window to it.
    CHECK(contains(m.worst, 5, 9));
}

TEST_CASE("worst_region_counts_non_finite_values_and_breaks_ties_in_row_major_order",
          "[unit][error_maps]") {
    std::vector<float> values(8 * 6, 0.0f);
    // Ties: every window has mean 0, so the first position wins.
    PixelRegion r = worst_region(values, 8, 6, 3);
    CHECK(r.x == 0);
    CHECK(r.y == 0);
    CHECK(r.width == 3);
    values[4 * 8 + 6] = std::numeric_limits<float>::infinity();
    values[1 * 8 + 1] = 50.0f;
    r = worst_region(values, 8, 6, 3, 100.0);
    CHECK(contains(r, 6, 4));
    CHECK_FALSE(contains(r, 1, 1));
    // A window larger than the image is clipped to it.
    r = worst_region(values, 8, 6, 32);
    CHECK(r.width == 8);
    CHECK(r.height == 6);
    CHECK(worst_region(values, 8, 5, 3).width == 0); // size mismatch
}

TEST_CASE("crop_and_zoom_copy_the_right_pixels", "[unit][error_maps]") {
    ImageRGBA8 img{4, 3, {}};
    for (uint8_t i = 0; i < 12; ++i)
        img.rgba.insert(img.rgba.end(), {i, uint8_t(i * 2), uint8_t(i * 3), 255});
    const ImageRGBA8 c = crop(img, PixelRegion{1, 1, 2, 5}); // clipped to 2x2
    REQUIRE(c.width == 2);
    REQUIRE(c.height == 2);
    CHECK(pixel(c, 0, 0) == std::array<uint8_t, 3>{5, 10, 15});
    CHECK(pixel(c, 1, 1) == std::array<uint8_t, 3>{10, 20, 30});
    const ImageRGBA8 z = zoom_nearest(c, 3);
    REQUIRE(z.width == 6);
    REQUIRE(z.height == 6);
    CHECK(pixel(z, 2, 2) == pixel(c, 0, 0));
    CHECK(pixel(z, 3, 2) == pixel(c, 1, 0));
    CHECK(pixel(z, 5, 5) == pixel(c, 1, 1));
    CHECK(crop(img, PixelRegion{4, 0, 2, 2}).width == 0);
    // Context around a window: grown on every side, clipped at the image's edges.
    const PixelRegion g = grown_region(PixelRegion{1, 1, 2, 1}, 1, 4, 3);
    CHECK((g.x == 0 && g.y == 0 && g.width == 4 && g.height == 3));
    const PixelRegion inner = grown_region(PixelRegion{10, 20, 8, 8}, 4, 64, 64);
    CHECK((inner.x == 6 && inner.y == 16 && inner.width == 16 && inner.height == 16));
    ImageRGBA8 o = img;
    outline_region(o, PixelRegion{1, 0, 3, 3}, {9, 8, 7});
    CHECK(pixel(o, 1, 0) == std::array<uint8_t, 3>{9, 8, 7});
    CHECK(pixel(o, 3, 2) == std::array<uint8_t, 3>{9, 8, 7});
    CHECK(pixel(o, 2, 1) == pixel(img, 2, 1)); // the inside is left alone
    CHECK(pixel(o, 0, 1) == pixel(img, 0, 1));
}

TEST_CASE("the_colour_bar_ends_are_the_heat_map_ends", "[unit][heat_map]") {
    for (const HeatScale& scale : {ciede2000_scale(), flip_scale()}) {
        const ImageRGBA8 bar = color_bar(scale, 100, 4);
        const std::vector<float> ends{float(scale.lo), float(scale.hi), float(scale.hi * 3)};
        const ImageRGBA8 map = heat_map(ends, 3, 1, scale);
        CHECK(pixel(bar, 0, 0) == pixel(map, 0, 0));
        CHECK(pixel(bar, 99, 3) == pixel(map, 1, 0));
        CHECK(pixel(map, 2, 0) == pixel(map, 1, 0)); // values above hi clip
        CHECK(pixel(bar, 0, 0) == magma(0.0));
        CHECK(pixel(bar, 99, 0) == magma(1.0));
        CHECK(scale_position(scale, scale.ticks.front()) == 0.0);
        CHECK(scale_position(scale, scale.ticks.back()) == 1.0);
    }
    CHECK(magma(0.0) == std::array<uint8_t, 3>{0, 0, 4});
    CHECK(magma(1.0) == std::array<uint8_t, 3>{252, 253, 191});
    CHECK(ciede2000_scale().ticks[1] == kJustNoticeableDeltaE);
}

TEST_CASE("magma_gets_lighter_all_the_way_and_non_finite_values_are_green", "[unit][heat_map]") {
    double previous = -1.0;
    for (int i = 0; i <= 64; ++i) {
        const std::array<uint8_t, 3> c = magma(i / 64.0);
        const double lightness = srgb8_to_lab(c[0], c[1], c[2]).L;
        INFO("t = " << i / 64.0);
        CHECK(lightness > previous);
        previous = lightness;
    }
    const std::vector<float> values{std::nanf(""), 0.5f};
    const ImageRGBA8 map = heat_map(values, 2, 1, flip_scale());
    CHECK(pixel(map, 0, 0) == kHeatNonFiniteColor);
    CHECK(pixel(map, 1, 0) == magma(0.5));
    CHECK(heat_map(values, 3, 1, flip_scale()).rgba.empty());
}
