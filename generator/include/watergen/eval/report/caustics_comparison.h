// `watergen caustics` as a library call: the caustics passes (area ratio, photon splatting) of
// one wave model drawn on the device against the CPU photon reference of the same values: the
// textures as PNG images, the pass time on the device, each method's error against the
// reference, and the light the area ratio's clamp loses; written into <out>/caustics-<waves>/
// whole (a staged directory swapped in) with caustics.json.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "watergen/eval/draw/caustics_pass_draw.h"
#include "watergen/eval/draw/draw_device.h"
#include "watergen/water/presets.h"

namespace watergen {

struct CausticsComparisonRequest {
    std::string waves = "gerstner";
    std::string method = "both";    // area_ratio, photon_splat or both
    const Preset* preset = nullptr; // its values (its sun) over the passes' defaults
    double depth = 3, clamp = 5;    // bottom depth below the water level (m), area ratio clamp
    uint32_t size = 256;            // texture side
    uint32_t draws = 5;             // timed draws per method
    uint32_t cells = 0;             // grid cells per texel side; 0: default_cells_per_texel
    std::filesystem::path out = "out/caustics";
};

// What needs no device: the passes built (as a build of a material of the preset alone ships
// them) and the CPU reference of their values.
struct CausticsComparisonSetup {
    CausticsComparisonRequest request;
    std::map<std::string, std::vector<double>> given; // the preset's values, depth, clamp, window
    double margin = 0;                                // the grid's reach beyond the window, m
    std::vector<CausticsPassBuild> builds;
    CausticsSetup reference_setup;
    CausticsImage reference;
    Diagnostics diagnostics; // of a pass that did not build
    std::string error;       // the reference's failure
    RunStatus status = RunStatus::Ok;
};

// Cost: the passes' builds (about 0.1 s each) and 64 photons per texel on the CPU.
CausticsComparisonSetup prepare_caustics_comparison(const CausticsComparisonRequest& request);

struct CausticsMethodFigures {
    CausticsMethod method = CausticsMethod::AreaRatio;
    double steady_ms = 0, mean = 0, mean_unclamped = 0, max_abs = 0, rmse = 0, glsl_vs_hlsl = 0;
    double clamp_lost() const { return mean_unclamped - mean; }
};

struct CausticsComparison {
    std::vector<CausticsMethodFigures> methods; // in the order drawn
    std::filesystem::path dir;                  // written
    std::string error;
    RunStatus status = RunStatus::Ok;
};

// Draws each pass (the area ratio once more unclamped, untimed), encodes the PNGs and writes
// the directory. Cost: per method two pipelines (JIT) and the draws.
CausticsComparison run_caustics_comparison(VulkanRunner& runner,
                                           const CausticsComparisonSetup& setup);

} // namespace watergen
