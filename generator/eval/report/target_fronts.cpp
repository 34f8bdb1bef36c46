#include "watergen/eval/report/target_fronts.h"

#include <algorithm>
#include <cmath>

#include "watergen/eval/report/report_svg.h"

namespace watergen {

bool TargetFronts::any_disagreement() const {
    return std::find(disagree.begin(), disagree.end(), true) != disagree.end();
}

double target_cost(const CompareVariant& variant, const std::string& target) {
    if (target == "lavapipe") return variant.cost;
    const auto it = variant.target_costs.find(target);
    return it == variant.target_costs.end() ? 0 : it->second;
}

TargetFronts target_fronts(const CompareReport& report, const ResolvedErrors& errors) {
    TargetFronts out;
    const bool lavapipe = !report.variants.empty() &&
                          std::all_of(report.variants.begin(), report.variants.end(),
                                      [](const CompareVariant& v) { return v.cost != 0; });
    if (lavapipe) out.targets.push_back("lavapipe");
    out.targets.insert(out.targets.end(), report.cost_targets.begin(), report.cost_targets.end());
    const std::size_t p99 = static_cast<std::size_t>(ErrorColumn::Ciede2000P99);
    for (const std::string& t : out.targets) {
        std::vector<ScatterPoint> points;
        for (std::size_t v = 0; v < report.variants.size(); ++v) {
            const double x = target_cost(report.variants[v], t);
            points.push_back({"", "", x != 0 ? x : std::nan(""), errors.summaries[v][p99]});
        }
        std::vector<bool> on(report.variants.size(), false);
        for (std::size_t i : pareto_front(points))
            on[i] = true;
        out.on_front.push_back(std::move(on));
    }
    out.disagree.assign(report.variants.size(), false);
    for (std::size_t v = 0; v < report.variants.size(); ++v) {
        bool some = false, all = true;
        for (const auto& on : out.on_front) {
            some = some || on[v];
            all = all && on[v];
        }
        out.disagree[v] = some && !all;
    }
    return out;
}

std::string disagreement_text(const TargetFronts& fronts, std::size_t variant) {
    if (!fronts.disagree[variant]) return "";
    std::string on, off;
    for (std::size_t t = 0; t < fronts.targets.size(); ++t) {
        std::string& list = fronts.on_front[t][variant] ? on : off;
        list += (list.empty() ? "" : ", ") + fronts.targets[t];
    }
    return "on the front of " + on + "; dominated on " + off;
}

} // namespace watergen
