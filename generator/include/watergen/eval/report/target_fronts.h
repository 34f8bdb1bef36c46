// Where cost targets disagree: per target, the Pareto front of cost against the worst view's
// p99 CIEDE2000 (report_svg.h's pareto_front), and the variants on one target's front that
// another target's costs dominate. lavapipe counts as a target when every variant has its count.
#pragma once

#include <string>
#include <vector>

#include "watergen/eval/report/compare_table.h"

namespace watergen {

struct TargetFronts {
    std::vector<std::string> targets;        // "lavapipe" first when costed, then cost_targets
    std::vector<std::vector<bool>> on_front; // [target][variant]
    std::vector<bool> disagree;              // [variant]: on some front, off another
    bool any_disagreement() const;
};

// The variant's cost on `target` ("lavapipe": CompareVariant::cost); 0 when not measured.
double target_cost(const CompareVariant& variant, const std::string& target);

TargetFronts target_fronts(const CompareReport& report, const ResolvedErrors& errors);

// "on the fronts of lavapipe, rdna2; dominated on gcn4" for a variant that disagrees, else "".
std::string disagreement_text(const TargetFronts& fronts, std::size_t variant);

} // namespace watergen
