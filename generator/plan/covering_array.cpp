#include "watergen/plan/covering_array.h"

#include <set>
#include <tuple>

#include "watergen/plan/variant_space.h"

namespace watergen {

namespace {

using Pair = std::tuple<size_t, size_t, size_t, size_t>; // axis a, choice i, axis b > a, choice j

size_t axis_position(const std::string& name) {
    return static_cast<size_t>(find_axis(name) - axes().data());
}

// The built-in rules are pairwise, so a pair is feasible when the two choices alone obey them.
bool compatible(const Variant& partial, const std::vector<bool>& set) {
    static const std::vector<Rule> rules = builtin_rules();
    for (const auto& r : rules) {
        const size_t ia = axis_position(r.axis), ib = axis_position(r.other_axis);
        if (!set[ia] || !set[ib] || partial.choices[ia] != r.choice) continue;
        bool listed = false;
        for (const auto& c : r.other_choices)
            listed = listed || partial.choices[ib] == c;
        if (listed != (r.kind == Rule::Kind::Requires)) return false;
    }
    return true;
}

// The geometry axis stays at the screen pass: a mesh's fragment is the same nodes, fed by its
// vertex or evaluation stage instead of a search, and no CPU evaluation of a fragment alone
// can check a rasterised mesh pixel by pixel (render_geometry draws meshes against the exact
// surface instead).
bool covered_axis(const AxisInfo& axis) {
    return axis.name != "geometry";
}

} // namespace

std::vector<Variant> pairwise_covering_variants() {
    const auto& list = axes();
    const size_t n = list.size();
    std::set<Pair> uncovered;
    for (size_t a = 0; a < n; ++a)
        for (size_t b = a + 1; b < n && covered_axis(list[a]); ++b)
            if (covered_axis(list[b]))
                for (size_t i = 0; i < list[a].choices.size(); ++i)
                    for (size_t j = 0; j < list[b].choices.size(); ++j) {
                        Variant v = default_variant();
                        std::vector<bool> set(n, false);
                        v.choices[a] = list[a].choices[i].name;
                        v.choices[b] = list[b].choices[j].name;
                        set[a] = set[b] = true;
                        if (compatible(v, set)) uncovered.insert({a, i, b, j});
                    }

    std::vector<Variant> result;
    while (!uncovered.empty()) {
        const auto [a0, i0, b0, j0] = *uncovered.begin();
        Variant v = default_variant();
        std::vector<size_t> pick(n, 0);
        std::vector<bool> set(n, false);
        v.choices[a0] = list[a0].choices[i0].name;
        v.choices[b0] = list[b0].choices[j0].name;
        pick[a0] = i0;
        pick[b0] = j0;
        set[a0] = set[b0] = true;
        for (size_t a = 0; a < n; ++a) {
            if (set[a]) continue;
            size_t best = SIZE_MAX, best_gain = 0;
            for (size_t i = 0; i < list[a].choices.size(); ++i) {
                v.choices[a] = list[a].choices[i].name;
                set[a] = true;
                const bool ok = compatible(v, set);
                set[a] = false;
                if (!ok) continue;
                size_t gain = 0;
                for (size_t b = 0; b < n; ++b)
                    if (set[b])
                        gain += uncovered.count(b < a ? Pair{b, pick[b], a, i}
                                                      : Pair{a, i, b, pick[b]});
                if (best == SIZE_MAX || gain > best_gain) {
                    best = i;
                    best_gain = gain;
                }
            }
            pick[a] = best;
            v.choices[a] = list[a].choices[best].name;
            set[a] = true;
        }
        for (size_t a = 0; a < n; ++a)
            for (size_t b = a + 1; b < n; ++b)
                uncovered.erase({a, pick[a], b, pick[b]});
        result.push_back(v);
    }
    return result;
}

} // namespace watergen
