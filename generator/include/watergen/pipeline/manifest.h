// manifest.json: what a build produced, per variant its key, short hash, content hash, chosen
// nodes, folded parameters and removed terms (with the scene facts behind them), files per
// target, reflection (bindings, uniform layout) and SPIR-V instruction counts. Sorted by
// (scene, key) and free of paths, times and other run-dependent data: byte-identical for equal
// inputs, whether the material came from C++ or from a file.
#pragma once

#include <string>
#include <vector>

#include "watergen/pipeline/parallel_build.h"
#include "watergen/plan/scene_pruning.h"

namespace watergen {

// One scene of a build: a ScenePlan, or the material's whole space unpruned (plan == nullptr).
struct ManifestScene {
    std::string name;
    const ScenePlan* plan = nullptr;
    size_t variants = 0;
};

std::string manifest_json(const Material& material, const std::vector<ManifestScene>& scenes,
                          const std::vector<BuildJob>& jobs, const std::vector<JobResult>& results);

// Directory of a variant inside the output, e.g. "open_ocean/fresnel-schlick_...".
std::string variant_directory(const std::string& scene, const Variant& v);

} // namespace watergen
