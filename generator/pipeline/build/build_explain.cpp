#include "watergen/pipeline/build/build_explain.h"

namespace watergen {

std::unique_ptr<BuildExplanation> explain_build(const Material& material,
                                                const std::vector<SceneFacts>& scenes,
                                                const std::string& detail_key, size_t sample,
                                                size_t listed, Diagnostics& diagnostics) {
    auto plan = plan_build(material, scenes, diagnostics);
    if (!plan) return nullptr;
    auto out = std::make_unique<BuildExplanation>();
    out->plan = std::move(*plan); // its scenes stay where they are: the plans point into them
    out->explanation = explain_plans(material, out->plan.scenes, detail_key, sample, listed);
    return out;
}

} // namespace watergen
