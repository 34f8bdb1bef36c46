// The synthetic scene's caustics textures (render/scene_caustics_inputs.cpp): the tile's
// layout and energy, the map's light over the window, and that both are deterministic.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "watergen/eval/scene/synthetic_scene.h"

using namespace watergen;

namespace {

struct Stats {
    double mean = 0, lo = 1e30, hi = -1e30;
};

// Over texels [0, n) x [0, n) of the r channel.
Stats stats(const TextureData& t, uint32_t n) {
    Stats s;
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i) {
            const double v = t.rgba[(size_t(j) * t.width + i) * 4];
            s.mean += v;
            s.lo = std::min(s.lo, v);
            s.hi = std::max(s.hi, v);
        }
    s.mean /= double(n) * n;
    return s;
}

} // namespace

TEST_CASE("the_scene_caustics_textures_are_tiles_of_light_from_the_photon_reference",
          "[views][caustics]") {
    const SyntheticScene a = make_synthetic_scene(32, 32);
    const SyntheticScene b = make_synthetic_scene(32, 32);
    for (const char* name : {"caustics_tile", "caustics_map"}) {
        INFO(name);
        const TextureData& t = a.textures.at(name);
        REQUIRE(t.width == 64);
        REQUIRE(t.height == 64);
        CHECK(t.rgba == b.textures.at(name).rgba); // deterministic
        for (size_t p = 0; p < t.rgba.size(); p += 4) {
            REQUIRE(std::isfinite(t.rgba[p]));
            CHECK(t.rgba[p + 1] == t.rgba[p]);
            CHECK(t.rgba[p + 3] == 1.0f);
        }
    }
    // The tile: texel 63 repeats texel 0 (tile_coordinate's layout), and over its 63 x 63
    // period the light is that of flat water (the reference conserves it over a period).
    const TextureData& tile = a.textures.at("caustics_tile");
    for (uint32_t k = 0; k < 64; ++k) {
        CHECK(tile.rgba[(size_t(k) * 64 + 63) * 4] == tile.rgba[(size_t(k) * 64) * 4]);
        CHECK(tile.rgba[(size_t(63) * 64 + k) * 4] == tile.rgba[size_t(k) * 4]);
    }
    const Stats ts = stats(tile, 63);
    const Stats ms = stats(a.textures.at("caustics_map"), 64);
    std::printf("caustics tile: mean %.6f, min %.3f, max %.3f; map: mean %.4f, min %.3f, max "
                "%.3f\n",
                ts.mean, ts.lo, ts.hi, ms.mean, ms.lo, ms.hi);
    CHECK(ts.mean == Approx(1.0).margin(1e-6));
    // Below the focal depth: the light varies, but smoothly (no texel is a spike).
    CHECK(ts.lo > 0.5);
    CHECK(ts.hi < 2.0);
    CHECK(ts.hi - ts.lo > 0.3);
    // The map: the scene's Gerstner waves over the 10 m window, light entering from its sides.
    CHECK(ms.mean == Approx(1.0).margin(0.05));
    CHECK(ms.hi - ms.lo > 0.3);
    // The map follows the sun; the tile does not.
    const SyntheticScene other = make_synthetic_scene(32, 32, *find_scene_view("sun_glint"));
    CHECK(other.textures.at("caustics_tile").rgba == tile.rgba);
    CHECK(other.textures.at("caustics_map").rgba != a.textures.at("caustics_map").rgba);
}
