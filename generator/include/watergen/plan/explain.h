// `watergen explain` as data: the material's space and rules; per scene what it skips (the
// reasons its plan kept), fixes and emits, and what folding removes from the variants it
// reaches, each with the scene fact behind it; then the variants no scene reaches. Nothing is
// compiled: composing and folding take milliseconds a variant.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "watergen/plan/scene_pruning.h"

namespace watergen {

struct MaterialOverview {
    std::string name, file; // file "" when built in
    size_t variants = 0, full_space = 0;
    std::string offered; // "fresnel 2 x specular 2", "" when every axis has one choice
    std::vector<std::string>
        rules; // the material's own: "precision=half excludes fresnel in {exact}: why [where]"
};

struct ExplainedRewrite {
    std::string origin, what, because;
};

// Every rewrite of one variant (explain --variant).
struct VariantRewrites {
    std::string key;
    size_t live_before = 0, live_after = 0;
    std::vector<ExplainedRewrite> rewrites;
};

struct SceneExplanation {
    const ScenePlan* plan = nullptr;            // name, file, platforms, targets, skipped groups
    std::map<std::string, std::string> fixes;   // parameter -> the fact that fixes it
    size_t folded = 0, step = 1;                // variants folded: every step-th of plan->variants
    std::map<std::string, size_t> removals;     // "removes term t (node): because" -> variants
    std::vector<std::string> same;              // "key\n      is the same shader as key"
    std::map<std::string, size_t> uncomposable; // first diagnostic -> variants
    size_t live_before = 0, live_after = 0;     // over the folded variants
    std::optional<VariantRewrites> detail;
};

// A variant no scene reaches, with every scene's reason (SkippedGroup::text()).
struct UnreachedVariant {
    std::string key;
    std::vector<std::pair<std::string, std::string>> reasons; // scene name, reason
};

struct Explanation {
    MaterialOverview material;
    std::vector<SceneExplanation> scenes; // in the order of the plans
    // The first variants no scene reaches, in enumeration order (all, or as many as asked for),
    // and how many there are: the full space with one scene leaves millions unreached.
    std::vector<UnreachedVariant> unreached;
    size_t unreached_count = 0;
};

// Explains the plans of `scenes` (planned against `material`, which must outlive the
// result's plan pointers). Folds at most `sample` variants per scene, evenly spaced (0: all),
// always including `detail_key` ("" for none), whose rewrites are listed one by one. Lists the
// first `listed` variants no scene reaches (0: all) and counts them all.
Explanation explain_plans(const Material& material, const std::vector<ScenePlan>& scenes,
                          const std::string& detail_key, size_t sample, size_t listed = 0);

} // namespace watergen
