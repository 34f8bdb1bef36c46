// The comparison report's "Caustics passes" section (compare_report.h) and compare.json's
// "caustics_passes": per pass the compared variants read, its texture beside the CPU photon
// reference and their difference, its draw time on the device and its error against the
// reference. Plain figures: the caller (watergen compare, compare_caustics.h) measures them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace watergen {

struct CausticsPassFigures {
    std::string name;                    // e.g. "area_ratio, gerstner waves"
    uint32_t texels = 0;                 // texture side
    std::vector<double> pass, reference; // texels x texels intensities, row-major (row = z)
    double max_abs = 0, rmse = 0, mean_difference = 0; // pass against reference
    double mean = 0, reference_mean = 0;
    double glsl_vs_hlsl = 0; // max abs between the two paths' textures
    // Draw time over the rounds (each round's median draw): median and range, ms; and the ratio
    // to the first pass with its 95% interval (1 for the first pass itself).
    double median_ms = 0, min_ms = 0, max_ms = 0;
    uint32_t rounds = 0;
    double ratio = 0, ratio_lo = 0, ratio_hi = 0;
};

// The section's HTML, "" for no passes; `note` says how they were drawn and timed.
std::string caustics_passes_html(const std::vector<CausticsPassFigures>& passes,
                                 const std::string& note);

// compare.json's "caustics_passes": {"note": ..., "passes": [...]}.
nlohmann::ordered_json caustics_passes_json(const std::vector<CausticsPassFigures>& passes,
                                            const std::string& note);

} // namespace watergen
