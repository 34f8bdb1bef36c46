// The stability bench (`watergen bench stability`): how far the GPU's water is from the CPU
// evaluator in double as the game clock runs and the camera travels. Games run for hours and
// their cameras cross kilometres; a wave phase of 10^6 rad keeps about 0.06 rad in binary32,
// and Vulkan guarantees sin and cos to 2^-11 only inside [-pi, pi]. Every figure is against the
// same graph in double over the same scene, moved by its world offset (SceneView::world_offset:
// the seabed, the spheres, the position texture, the depth buffer and the optics move with the
// eye), so growth with time or distance is the shader's rounding, not a change of scene.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "watergen/eval/bench/stability_before.h"
#include "watergen/eval/draw/variant_render.h"

namespace watergen {

// One scene of the sweep: a view, the time and the world offset (along +x).
struct StabilityPoint {
    std::string sweep; // "view" (each view at the origin and the far corner), "time", "distance",
                       // "elevation"
    std::string view;  // a scene view's name; "elevation" points: grazing at that pitch
    double time = 0;   // s
    double offset = 0; // m from the world origin, along +x
    double elevation = 0; // degrees below the horizon of the view's centre; 0: the view's own
};

// The scene a point draws, size x size: its view (at its pitch, for an elevation), moved by its
// offset, at its time (the caustics map made again for it).
SyntheticScene stability_scene(const StabilityPoint& p, uint32_t size);

// The points a sweep of these times, offsets and elevations runs: every view at the origin and
// at (corner_time, corner_offset); the time and distance sweeps in sun_glint; the elevations in
// grazing at the origin and the corner.
std::vector<StabilityPoint> stability_points(const std::vector<double>& times,
                                             const std::vector<double>& offsets,
                                             const std::vector<double>& elevations,
                                             double corner_time, double corner_offset);

// Defaults: the sweep. Times 0, 1 h, 1 day, 1 week, 1 year (365.25 days); offsets 0,
// 1, 10, 100, 1000 km; elevations 10, 3, 1, 0.5 degrees; the corner 1 week and 100 km.
std::vector<double> default_stability_times();
std::vector<double> default_stability_offsets();
std::vector<double> default_stability_elevations();

// A variant of the sweep: its waves, precision and geometry choices (other axes at the
// default, normals analytic), at one size.
struct StabilityCase {
    std::string waves, precision, geometry;
    uint32_t size = 512;
};

// A render against the CPU in double, one language path, over the pixels whose colour is
// continuous under float rounding: float bound (RenderSettings::float_bound) at most
// kDiscontinuousBound. A pixel past it sits on a discontinuity (a surface search taking another
// crest, a depth-buffer shoreline rounding to sand or water): its difference from double is the
// contrast across the edge, not a rounding that conditioning could bound. max_abs: the largest
// difference there; past_bound: the most a difference exceeds its pixel's float bound (what
// rounding the conditioned formula does not explain); discontinuous: the pixels left out. An
// unconditioned phase moves by radians under a one-ulp move of the time, so its pixels' bounds
// are wide and show in that count.
inline constexpr float kDiscontinuousBound = 0.01f;
struct ContinuousError {
    double max_abs = 0, past_bound = 0;
    uint64_t discontinuous = 0;
};
ContinuousError continuous_error(const VariantRender& r, size_t path);

struct StabilityRow {
    StabilityCase what;
    StabilityPoint where;
    std::string key;
    // GPU against the CPU in double, per language path (GLSL, HLSL): max abs over linear RGB
    // and the 99th percentile of CIEDE2000. A mesh variant's CPU image is the exact surface's,
    // so its figure includes the grid's own geometric error (the same at every point).
    std::array<double, 2> max_abs{}, de00_p99{};
    ContinuousError
        continuous{}; // the GLSL path's (screen pass: the mesh's CPU image has no bound)
    ContinuousError origin_continuous{}; // the same case and view's at t = 0, offset 0
    // Pixels over the tolerance plus the float bound (screen pass only: GPU against CPU float).
    std::array<uint64_t, 2> over_bound{};
    uint64_t gpu_nan_inf = 0;   // non-finite GPU pixels where the CPU's are finite
    double ratio_to_origin = 0; // GLSL max abs over the same case and view at t = 0, offset 0
    double ratio_de00 = 0;      // the same for dE00 p99 (0 where the origin's is 0)
    // A half screen-pass case also in 16-bit arithmetic on the GPU (render_strict_half: lavapipe
    // runs relaxed precision at 32 bits, so the figures above are the float ones), against its
    // own reference, the CPU evaluator's half model of the same graph: GLSL max abs, dE00 p99,
    // most binary16 ulps apart, and the max abs over the origin's. NaN (-1) where not drawn.
    double strict_max_abs = NAN, strict_de00 = NAN, strict_ratio = NAN;
    int64_t strict_max_ulps = -1;
    // The same case and point in the run given as --before (NaN: none, or no such row there).
    StabilityBefore before{};
};

// How far a figure may grow from its case's at the origin: at most `max_ratio` times it, or up
// to a floor so small that a few float roundings double it: max abs 1e-5 (84 float ulps of a
// unit colour, a fifth of the renders' agreement tolerance 5e-5), dE00 p99 0.01 (a hundredth of
// a just-noticeable difference). NaN is never within.
inline constexpr double kStabilityMaxAbsFloor = 1e-5, kStabilityDe00Floor = 0.01;
inline bool stability_within(double value, double at_origin, double max_ratio, double floor) {
    return value <= std::max(max_ratio * at_origin, floor);
}
// The row's GLSL figures within stability_within of the origin's: where the row has a float
// bound, the error past it (floor kAgreementTolerance) and the discontinuous pixels (floor 0.1%
// of the image), else the max abs; the dE00 p99; the strict half figure where drawn.
bool stability_row_within(const StabilityRow& r, double max_ratio);

struct StabilityBench {
    std::vector<StabilityRow> rows;
    std::string csv, json, html; // stability.csv, stability.json, stability.html
    std::string error;           // "<variant key> <point>: <what>"
    bool ok() const { return error.empty(); }
};

// The variant a case draws, or why it cannot be made.
std::optional<Variant> stability_variant(const StabilityCase& c, std::string& error);

// What:   render_variant of every case at every point (one build per case), with both
//         language paths, the CPU double image and the float bound; rows in case order, then
//         point order, each joined to `before`'s row of its case and point (may be null).
//         `progress` (may be null) is told each row as it is done.
// Cost:   per row two pipelines and six CPU evaluations, and with strict half three more
//         builds and a CPU half evaluation: about 6 s a row at 512x512 on this project's 2-core
//         machine (979 s for Gerstner's 168 rows at 15a4795); 1024x1024 has four times the pixels.
StabilityBench run_stability_bench(VulkanRunner& runner, const std::vector<StabilityCase>& cases,
                                   const std::vector<StabilityPoint>& points,
                                   void (*progress)(const StabilityRow&) = nullptr,
                                   const StabilityBeforeTable* before = nullptr);

} // namespace watergen
