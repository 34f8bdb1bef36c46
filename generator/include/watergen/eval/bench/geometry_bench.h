// The geometry bench (`watergen bench geometry`): per view of the synthetic scene, one variant
// drawn as the screen pass and as meshes and tessellated meshes of several grid densities, each
// image against the exact surface (the screen pass with its search run to convergence, in
// double on the CPU), with the grid's vertex and primitive counts and the draw time on the
// device, interleaved with the screen pass and A/A-checked. lavapipe's draw time is a CPU's.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "watergen/eval/image/image_metrics.h"
#include "watergen/eval/measure/interleaved_timing.h"
#include "watergen/runner/vulkan_runner.h"
#include "watergen/runtime/water_grid.h"
#include "watergen/water/variant.h"

namespace watergen {

struct GeometryBenchRow {
    std::string view;
    std::string geometry;                  // screen_pass, mesh or tessellated
    WaterGridDesc grid{};                  // a mesh's
    double tess_max = 0;                   // a tessellated mesh's
    uint64_t vertices = 0, primitives = 0; // of the grid: triangles or patches
    uint64_t covered = 0;                  // pixels the draw wrote (all, for the screen pass)
    ImageErrorStats vs_exact;              // GLSL image against the exact surface
    double glsl_vs_hlsl = 0;               // max abs
    RatioInterval draw_time;               // steady draw time / the screen pass'
    double draw_ms = 0;                    // median steady draw
};

struct GeometryBenchSettings {
    uint32_t size = 512;
    std::vector<std::string> views; // scene_views() names; empty: every view
    std::vector<uint32_t> rings = {16, 32, 64, 128, 256};
    double spacing = 0.5;
    uint32_t levels = 10;
    // The tessellated rows: patches of `patch_spacing` m, 16 rings, factors up to each of these.
    double patch_spacing = 4.0;
    std::vector<double> tess_max = {4, 16};
    uint32_t rounds = 5, draws = 2; // interleaved timing
};

struct GeometryBench {
    std::string key; // the mesh variant's
    GeometryBenchSettings settings;
    std::vector<GeometryBenchRow> rows; // per view: the screen pass, meshes, tessellated
    bool timing_trustworthy = true;     // every view's A/A within +-3%
    std::string csv, json;              // geometry.csv, geometry.json
    std::string error;
    bool ok() const { return error.empty(); }
};

// What:   for each view, the exact surface of `variant` (its screen pass, search converged, in
//         double) and, timed together, its screen pass, its mesh at each ring count and its
//         tessellated mesh at each tess_max; errors, counts and draw-time ratios.
// Output: rows by view, the first failure otherwise.
// Cost:   per view one CPU evaluation in double (about 10 s at 512^2) and 2 + rings + tess
//         pipelines drawn rounds x draws times.
GeometryBench run_geometry_bench(VulkanRunner& runner, const Variant& variant,
                                 const GeometryBenchSettings& settings);

// The coarsest ring count of a view's mesh rows whose CIEDE2000 p99 against the exact surface
// is at most `budget`; 0 when none is.
uint32_t rings_within(const GeometryBench& bench, const std::string& view, double budget);

} // namespace watergen
