// The caustics passes of a `watergen compare`: every variant with caustics=area_ratio or
// photon_splat renders over its own pass's map, the pass of its method and wave model drawn
// for each view (scene_caustics_pass.h) the first time a variant needs it; then the passes are
// timed on the device, interleaved (interleaved_timing.h) in the first view, and measured
// against the CPU photon reference there: the figures of the report's "Caustics passes".
#pragma once

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "watergen/eval/draw/scene_caustics_pass.h"
#include "watergen/eval/measure/interleaved_timing.h"
#include "watergen/eval/report/caustics_report.h"

namespace watergen {

// One pass as the report shows it: its texture and the reference in the first view, the error,
// and its draw time there over the interleaved rounds.
struct ComparedCausticsPass {
    std::string name;        // "area_ratio, gerstner waves"
    SceneCausticsPass first; // drawn for the first view (texture, reference, errors)
    // Per round the median of its draws; over the rounds their median and range (ms).
    std::vector<double> round_ms;
    double median_ms = 0, min_ms = 0, max_ms = 0;
    RatioInterval vs_first_pass; // its time over the first pass's, paired by round
};

// The report's figures of timed passes.
std::vector<CausticsPassFigures>
caustics_pass_figures(const std::vector<ComparedCausticsPass>& passes);

class CompareCaustics {
  public:
    // Each pass as a build of `material` ships it (build_caustics_pass_files).
    CompareCaustics(VulkanRunner& runner,
                    const std::vector<std::pair<std::string, SyntheticScene>>& views,
                    Material material = {});
    ~CompareCaustics();

    // CompareRequest::textures_for: the caustics_map of the built variant's pass in view
    // `view` (drawn on first use), or nothing for a variant without a pass.
    std::map<std::string, TextureData> textures_for(const VariantBuild& water, size_t view,
                                                    std::string* error);

    // The passes drawn so far, timed interleaved in the first view (`rounds` rounds of `draws`
    // draws each, the A/A of the first pass in *aa); empty when no variant had a pass.
    std::vector<ComparedCausticsPass> time(uint32_t rounds, uint32_t draws, RatioInterval* aa,
                                           std::string* error);

  private:
    struct Pass;
    VulkanRunner& runner_;
    const std::vector<std::pair<std::string, SyntheticScene>>& views_;
    Material material_;
    std::vector<std::unique_ptr<Pass>> passes_; // in the order first needed
};

} // namespace watergen
