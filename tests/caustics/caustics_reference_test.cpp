#include <cmath>

#include <catch2/catch.hpp>

#include "watergen/caustics/caustics_reference.h"

using namespace watergen;

namespace {

constexpr double kPi = 3.14159265358979323846;

CausticsImage run(const CausticsSetup& s) {
    std::string error;
    CausticsImage image = caustics_reference(s, &error);
    INFO(error);
    REQUIRE(error.empty());
    return image;
}

// A sine wave along x with `cycles` periods over a 10 m tile.
CausticsWave sine_along_x(double amplitude, int cycles) {
    CausticsWave w;
    w.amplitude = amplitude;
    w.frequency = 2 * kPi * cycles / 10.0;
    return w;
}

// Three waves that are periodic over the 10 m tile (integer cycles along each axis).
std::vector<CausticsWave> tile_waves(double steepness) {
    std::vector<CausticsWave> waves;
    const int cycles[3][2] = {{2, 1}, {-1, 3}, {4, -2}};
    const double amplitude[3] = {0.12, 0.06, 0.03};
    for (int i = 0; i < 3; ++i) {
        const double kx = 2 * kPi * cycles[i][0] / 10.0, kz = 2 * kPi * cycles[i][1] / 10.0;
        CausticsWave w;
        w.frequency = std::hypot(kx, kz);
        w.dir_x = kx / w.frequency;
        w.dir_z = kz / w.frequency;
        w.amplitude = amplitude[i];
        w.phase = 0.7 * i;
        w.steepness = steepness;
        waves.push_back(w);
    }
    return waves;
}

} // namespace

// Flat water: every texel receives exactly its photons, for a vertical and an oblique sun,
// periodic or not (the landing grid shifts, the bilinear splat keeps each texel's sum).
TEST_CASE("caustics_reference_flat_water_is_uniform", "[caustics]") {
    for (bool periodic : {true, false}) {
        for (auto sun : {std::array<double, 3>{0, -1, 0}, std::array<double, 3>{0.5, -0.6, 0.3}}) {
            CausticsSetup s;
            s.texels = 32;
            s.photons_per_side = 4;
            s.periodic = periodic;
            s.margin = 6; // beyond the 5 m bottom's refracted shift
            s.sun_direction = sun;
            const CausticsImage image = run(s);
            for (double v : image.intensity)
                REQUIRE(v == Approx(1.0).margin(1e-12));
        }
    }
}

// Over a whole period the beam's flux through the surface equals that through the plane: the
// area-weighted mean intensity is 1 (to rounding: the photon grid integrates the weights'
// trigonometric polynomials exactly), for sines and Gerstner waves under an oblique sun, and
// the caustics are far from uniform.
TEST_CASE("caustics_reference_conserves_energy_over_a_period", "[caustics]") {
    for (double steepness : {0.0, 0.6}) {
        CausticsSetup s;
        s.waves = tile_waves(steepness);
        s.sun_direction = {0.3, -0.9, -0.2};
        s.texels = 64;
        s.photons_per_side = 8;
        s.depth = 4;
        const CausticsImage image = run(s);
        INFO("steepness " << steepness);
        CHECK(image.shadowed == 0);
        CHECK(image.weight_sampled == Approx(1.0).margin(1e-9));
        CHECK(image.mean() == Approx(1.0).margin(1e-9));
        CHECK(image.standard_deviation() > 0.1);
    }
}

// One small-slope sine wave h = a sin(k x) under a vertical sun acts as a row of lenses: a
// photon lands at x + d (1 - 1/n) h'(x), so the intensity there is 1 / (1 + d (1 - 1/n) h''(x)),
// with the focus at d_f = 1 / ((1 - 1/n) a k^2). At d = d_f / 2 the crest focuses to 2 and the
// trough spreads to 2/3. a k = 0.005 keeps the small-slope terms below 1e-4; 256 texels per
// wavelength keep the splat's blur below 1e-3; tolerance 0.5% (measured 1.99902 and 0.66798).
TEST_CASE("caustics_reference_matches_the_small_slope_lens_of_a_sine_wave", "[caustics]") {
    CausticsSetup s;
    const CausticsWave w = sine_along_x(0.005 * 10 / (2 * kPi), 1);
    s.waves = {w};
    s.texels = 256;
    s.photons_per_side = 8;
    const double eta = 1 / s.ior;
    const double focus = 1 / ((1 - eta) * w.amplitude * w.frequency * w.frequency);
    s.depth = focus / 2;
    const CausticsImage image = run(s);
    // Crest at x = 2.5 m (texel 64), trough at x = 7.5 m (texel 192); texel centres at
    // (i + 0.5) * size / texels, so average the two texels around each.
    auto at = [&](uint32_t i) {
        return 0.5 * (image.intensity[10 * 256 + i - 1] + image.intensity[10 * 256 + i]);
    };
    CHECK(at(64) == Approx(2.0).epsilon(0.005));
    CHECK(at(192) == Approx(2.0 / 3.0).epsilon(0.005));
    CHECK(image.mean() == Approx(1.0).margin(1e-9));
}

// Caustics sharpen as the bottom deepens towards the focal depth: the spread of intensity and
// its peak grow monotonically, and stay finite past the focus, where the refracted grid folds.
TEST_CASE("caustics_reference_sharpens_towards_the_focal_depth", "[caustics]") {
    CausticsSetup s;
    const CausticsWave w = sine_along_x(0.05, 2);
    s.waves = {w};
    s.texels = 128;
    s.photons_per_side = 8;
    const double focus = 1 / ((1 - 1 / s.ior) * w.amplitude * w.frequency * w.frequency);
    double last_sd = 0, last_max = 0;
    for (double fraction : {0.2, 0.4, 0.6, 0.8}) {
        s.depth = fraction * focus;
        const CausticsImage image = run(s);
        INFO("depth " << s.depth << " m (" << fraction << " of the focus)");
        CHECK(image.standard_deviation() > last_sd);
        CHECK(image.max() > last_max);
        last_sd = image.standard_deviation();
        last_max = image.max();
    }
    s.depth = 3 * focus;
    const CausticsImage folded = run(s);
    for (double v : folded.intensity)
        REQUIRE(std::isfinite(v));
    CHECK(folded.mean() == Approx(1.0).margin(1e-9));
}

// Losses on flat water, against independent formulas: the sun 30 degrees off vertical enters
// at cos_i = cos 30; Snell gives cos_t; the unpolarised Fresnel transmittance and the
// attenuation over the refracted path d / cos_t multiply every texel.
TEST_CASE("caustics_reference_applies_fresnel_and_attenuation", "[caustics]") {
    CausticsSetup s;
    s.texels = 16;
    s.photons_per_side = 2;
    s.sun_direction = {std::sin(kPi / 6), -std::cos(kPi / 6), 0};
    s.fresnel = true;
    s.attenuation = 0.1;
    s.depth = 3;
    const double n = s.ior, ci = std::cos(kPi / 6);
    const double ct = std::sqrt(1 - (1 - ci * ci) / (n * n));
    const double rs = std::pow((ci - n * ct) / (ci + n * ct), 2);
    const double rp = std::pow((n * ci - ct) / (n * ci + ct), 2);
    const double expected = (1 - 0.5 * (rs + rp)) * std::exp(-0.1 * 3 / ct);
    const CausticsImage image = run(s);
    for (double v : image.intensity)
        REQUIRE(v == Approx(expected).epsilon(1e-12));
    CHECK(expected == Approx(0.708009).epsilon(1e-6)); // 0.978564 transmitted x 0.723518 left
}

TEST_CASE("caustics_reference_refuses_bad_input", "[caustics]") {
    const auto error_of = [](CausticsSetup s) {
        std::string error;
        const CausticsImage image = caustics_reference(s, &error);
        CHECK(image.intensity.empty());
        return error;
    };
    CausticsSetup s;
    s.sun_direction = {0, 1, 0};
    CHECK_THAT(error_of(s), Catch::Contains("sun_direction"));
    s = {};
    s.ior = 1;
    CHECK_THAT(error_of(s), Catch::Contains("ior"));
    s = {};
    s.texels = 0;
    CHECK_THAT(error_of(s), Catch::Contains("texels"));
    s = {};
    s.depth = -1;
    CHECK_THAT(error_of(s), Catch::Contains("depth"));
}
