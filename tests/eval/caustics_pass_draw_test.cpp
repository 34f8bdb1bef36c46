// The area-ratio caustics pass on lavapipe (256x256, the seed's caustics texture size), against
// physics and against the CPU photon reference. Figures measured on lavapipe are in comments.
#include <cmath>

#include <catch2/catch.hpp>

#include "shared_runner.h"
#include "watergen/eval/draw/caustics_pass_draw.h"

using namespace watergen;
using namespace watergen::test;

namespace {

constexpr double kPi = 3.14159265358979323846;
using Values = std::map<std::string, std::vector<double>>;

// Two waves periodic over the 10 m window (wavevectors of (3, 4) and (4, -3) cycles), in the
// parameters of `model`'s family, the sun oblique, no clamp.
Values periodic_waves(const std::string& model, double depth) {
    const std::string f = model == "gerstner" ? "gerstner" : "waves";
    return {{f + "_wave_count", {2}},
            {f + "_frequency", {2 * kPi * 5 / 10}},
            {f + "_frequency_gain", {1}},
            {f + "_amplitude", {0.06}},
            {f + "_amplitude_gain", {0.5}},
            {f + "_wave_directions", {0.6, 0.8, 0.8, -0.6, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}},
            {"caustics_window", {0, 0, 10}},
            {"caustics_depth", {depth}},
            {"caustics_clamp", {1e30}},
            {"sun_direction", {0.2, -0.9, 0.3}}};
}

struct Drawn {
    CausticsRender gpu;
    CausticsImage reference;
};

// Both paths on the GPU (the grid `margin` beyond the window: more than any ray's drift) and,
// for periodic waves, the periodic CPU reference.
Drawn draw(const std::string& model, const Values& v, bool reference = true, double margin = 3,
           CausticsMethod method = CausticsMethod::AreaRatio, uint32_t cells_per_texel = 2) {
    const CausticsPassBuild build = build_caustics_pass_files(Material{}, {method, model});
    REQUIRE(build.ok());
    const auto values = caustics_values(build, v);
    CausticsRenderSettings settings;
    settings.margin = margin;
    settings.cells_per_texel = cells_per_texel;
    Drawn d{render_caustics(shared_runner(), build, values, settings), {}};
    INFO(d.gpu.error);
    REQUIRE(d.gpu.ok());
    CHECK(d.gpu.glsl_vs_hlsl.max_abs == 0); // the two languages draw the same texture
    for (double x : d.gpu.intensity[0])
        REQUIRE(std::isfinite(x));
    if (reference) {
        CausticsSetup setup = caustics_reference_setup(model, values, settings.texels, margin);
        setup.periodic = true;
        std::string error;
        d.reference = caustics_reference(setup, &error);
        REQUIRE(error.empty());
    }
    return d;
}

double rmse(const std::vector<double>& a, const std::vector<double>& b) {
    double s = 0;
    for (size_t i = 0; i < a.size(); ++i)
        s += (a[i] - b[i]) * (a[i] - b[i]);
    return std::sqrt(s / double(a.size()));
}

} // namespace

// Flat water under an oblique sun shifts the light without spreading it: every texel 1, to the
// float rounding of one ratio (the beam offset is constant, so its derivatives are exactly 0),
// and exactly cells_per_texel^2 photons per texel (photons at cell centres, never on an edge).
TEST_CASE("caustics_passes_are_uniform_under_flat_water", "[render][caustics]") {
    for (CausticsMethod method : {CausticsMethod::AreaRatio, CausticsMethod::PhotonSplat})
        for (const char* model : {"sum_of_sines", "gerstner"}) {
            Values v = periodic_waves(model, 4);
            v[std::string(model) == "gerstner" ? "gerstner_wave_count" : "waves_wave_count"] = {0};
            const Drawn d = draw(model, v, false, 3, method);
            INFO(to_string(method) << " " << model);
            for (double x : d.gpu.intensity[0])
                REQUIRE(x == Approx(1.0).margin(1e-6));
        }
}

// Over whole periods the light through the surface all reaches the bottom: the area-weighted
// mean is 1 within 1% without the clamp (measured: area ratio 0.999957 sines, 0.999984
// Gerstner; photons 1.000000 and 0.999999), and the texture follows the photon reference.
// RMSE measured: area ratio 0.0043 and 0.023 (it samples each pixel's centre, the reference
// splats over a texel; they differ most at Gerstner's sharp peaks of up to 3.9); photons, 64
// per texel, 0.033 and 0.038 (binning noise: 0.096 at 16 per texel, 0.011 at 256).
TEST_CASE("caustics_passes_conserve_energy_and_match_the_reference", "[render][caustics]") {
    struct Case {
        CausticsMethod method;
        const char* model;
        double rmse_bound;
    };
    const Case cases[] = {{CausticsMethod::AreaRatio, "sum_of_sines", 0.01},
                          {CausticsMethod::AreaRatio, "gerstner", 0.05},
                          {CausticsMethod::PhotonSplat, "sum_of_sines", 0.05},
                          {CausticsMethod::PhotonSplat, "gerstner", 0.05}};
    for (const Case& c : cases) {
        const uint32_t cells = c.method == CausticsMethod::PhotonSplat ? 8 : 2;
        const Drawn d = draw(c.model, periodic_waves(c.model, 2), true, 3, c.method, cells);
        INFO(to_string(c.method) << " " << c.model);
        CHECK(mean_intensity(d.gpu.intensity[0]) == Approx(1.0).margin(0.01));
        CHECK(d.reference.mean() == Approx(1.0).margin(1e-9));
        CHECK(d.reference.standard_deviation() > 0.25); // caustics, not a flat texture
        CHECK(rmse(d.gpu.intensity[0], d.reference.intensity) < c.rmse_bound);
    }
}

// The clamp (HDRP's [0, 5]) loses the light of the sharpest peaks: nothing under a gentle
// surface whose peaks stay below 5, and a measurable share under Gerstner waves clamped at 2
// (measured 2.3%).
TEST_CASE("caustics_area_ratio_clamp_loses_only_the_peaks", "[render][caustics]") {
    Values sines = periodic_waves("sum_of_sines", 2);
    sines["caustics_clamp"] = {5};
    const Drawn gentle = draw("sum_of_sines", sines, false);
    CHECK(mean_intensity(gentle.gpu.intensity[0]) == Approx(1.0).margin(0.01));
    Values gerstner = periodic_waves("gerstner", 2);
    gerstner["caustics_clamp"] = {2};
    const Drawn clamped = draw("gerstner", gerstner, false);
    const double lost = 1 - mean_intensity(clamped.gpu.intensity[0]);
    WARN("energy lost by clamping Gerstner caustics at 2: " << lost);
    CHECK(lost > 0.001);
    CHECK(lost < 0.2);
}

// Deeper than the focus the refracted grid folds over (triangles turn over, new area 0 at the
// fold lines): still finite everywhere, and the folded layers together still carry the light
// (mean measured 1.0033).
// At 40 m the oblique sun shifts the light 11.7 m sideways: the grid reaches 15 m beyond.
TEST_CASE("caustics_area_ratio_stays_finite_where_the_grid_folds", "[render][caustics]") {
    const Drawn d = draw("gerstner", periodic_waves("gerstner", 40), false, 15);
    CHECK(mean_intensity(d.gpu.intensity[0]) == Approx(1.0).margin(0.01));
}
