// `watergen explain` as a library call: the scenes planned as `watergen build` plans them
// (plan_build), then explained (plan/explain.h): what each skips, fixes and folds away, and
// why, and the variants no scene reaches.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "watergen/pipeline/build/build_output.h"
#include "watergen/plan/explain.h"

namespace watergen {

struct BuildExplanation {
    BuildPlan plan; // the explanation's scene plans point into plan.scenes
    Explanation explanation;
};

// nullptr with the error in `diagnostics` on bad input (plan_build's). `material` must outlive
// the result. Folds at most `sample` variants per scene (0: all), always `detail_key`'s; lists
// the first `listed` variants no scene reaches (0: all).
std::unique_ptr<BuildExplanation> explain_build(const Material& material,
                                                const std::vector<SceneFacts>& scenes,
                                                const std::string& detail_key, size_t sample,
                                                size_t listed, Diagnostics& diagnostics);

} // namespace watergen
