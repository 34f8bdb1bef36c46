// The geometry bench (`watergen bench geometry`): per view of the synthetic scene, one variant
// drawn as the screen pass and as meshes and tessellated meshes of several grid densities, each
// image against the exact surface (the screen pass with its search run to convergence, in
// double on the CPU), with the grid's vertex and primitive counts and the draw time on the
// device, interleaved with the screen pass and A/A-checked; optionally the instructions
// lavapipe executes for each draw (valgrind) and ACO's statistics on AMD families (RADV's null
// device). lavapipe's draw time and instruction counts are a CPU's.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "watergen/eval/image/image_metrics.h"
#include "watergen/eval/measure/gpu_cost.h"
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
    // The LOD morph's share of the error: covered pixels whose point on the mean water level
    // lies where the grid blends toward the coarser level (0 < t < 1, morph_weights in
    // mesh_render.h), their fraction and CIEDE2000 p99, and the p99 of the other covered pixels.
    double morph_share = 0, morph_p99 = 0, still_p99 = 0;
    RatioInterval draw_time; // steady draw time / the screen pass'
    double draw_ms = 0;      // median steady draw
    // GeometryBenchSettings::count: the instructions lavapipe executes for the steady draw
    // (valgrind; 0 when not counted).
    uint64_t instructions = 0;
    // Per AMD target (GeometryBenchSettings::targets), an estimate of the frame's instructions
    // on it: ACO's vertex-stage instructions per vertex times the grid's vertices plus its
    // fragment instructions per pixel (loops weighted by trip count) times the covered pixels.
    // Overdraw and vertex reuse are not modelled; none for a tessellated mesh, whose
    // evaluation-stage invocations depend on the factors the control stage picks.
    std::map<std::string, double> aco_frame;
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
    // Count every row's steady draw under valgrind (a cost load does not move), the screen
    // pass twice in one run (two pipelines: the count's A/A).
    bool count = false;
    // AMD families (not lavapipe) whose ACO statistics to take for the three geometries.
    std::vector<GpuTarget> targets;
};

struct GeometryBench {
    std::string key; // the mesh variant's
    GeometryBenchSettings settings;
    std::vector<GeometryBenchRow> rows; // per view: the screen pass, meshes, tessellated
    bool timing_trustworthy = true;     // every view's A/A within +-3%
    std::map<std::string, RatioInterval> timing_aa; // per view: the screen pass against itself
    // settings.count: per view, the screen pass' two pipelines' counts differ by this
    // fraction (|second / first - 1|).
    std::map<std::string, double> count_aa;
    // settings.targets: per target, the GLSL then HLSL path of the screen pass, the mesh and
    // the tessellated mesh, in that order.
    std::vector<TargetCosts> aco;
    std::string csv, json; // geometry.csv, geometry.json
    std::string error;
    bool no_device = false; // the error is a target's missing null device (no radeon ICD)
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
