#include "watergen/eval/compare/pick.h"

#include <algorithm>
#include <set>

#include "watergen/eval/compare/compare_run.h"
#include "watergen/eval/draw/mesh_render.h"
#include "watergen/eval/draw/variant_render.h"
#include "watergen/ir/fold/ir_fold.h"

namespace watergen {

namespace {

// The axis' gold, when some reached choice is it or approximates it (directly or in a chain).
const ChoiceInfo* traded_gold(const AxisInfo& axis, const std::set<std::string>& reached) {
    const ChoiceInfo* gold = nullptr;
    for (const ChoiceInfo& c : axis.choices)
        if (c.gold) gold = &c;
    if (!gold) return nullptr;
    for (const std::string& r : reached)
        if (r == gold->name || approximates(axis, r, gold->name)) return gold;
    return nullptr;
}

} // namespace

PickPlan plan_pick(const ScenePlan& plan, const std::map<std::string, std::string>& hold) {
    PickPlan out;
    const auto& list = axes();
    out.gold = plan.variants.empty() ? default_variant() : plan.variants.front();
    std::vector<bool> held(list.size(), false);
    for (size_t a = 0; a < list.size(); ++a) {
        std::set<std::string> reached;
        for (const Variant& v : plan.variants)
            reached.insert(v.choices[a]);
        if (reached.size() < 2 && !hold.count(list[a].name)) continue;
        if (const ChoiceInfo* gold = traded_gold(list[a], reached);
            gold && !hold.count(list[a].name)) {
            out.gold.choices[a] = gold->name;
            continue;
        }
        held[a] = true;
        std::string choice;
        if (auto it = hold.find(list[a].name); it != hold.end())
            choice = it->second;
        else
            for (const ChoiceInfo& c : list[a].choices) // the richest: last in registry order
                if (reached.count(c.name)) choice = c.name;
        out.gold.choices[a] = choice;
        out.held.push_back(list[a].name + "=" + choice);
    }
    for (const Variant& v : plan.variants) {
        bool same_look = true;
        for (size_t a = 0; a < list.size(); ++a)
            same_look &= !held[a] || v.choices[a] == out.gold.choices[a];
        if (!same_look) {
            ++out.other_looks;
            continue;
        }
        const std::string relation = relation_to(v, out.gold);
        if (relation.rfind("different", 0) == 0) {
            ++out.other_looks;
            continue;
        }
        PickCandidate c;
        c.variant = v;
        c.relation = relation;
        out.candidates.push_back(c);
    }
    std::stable_sort(out.candidates.begin(), out.candidates.end(),
                     [](const PickCandidate& a, const PickCandidate& b) {
                         return a.relation == "reference" && b.relation != "reference";
                     });
    if (out.candidates.empty() || out.candidates.front().relation != "reference") {
        PickCandidate gold;
        gold.variant = out.gold;
        gold.relation = "reference";
        gold.reached = false;
        out.candidates.push_back(gold);
    }
    return out;
}

std::string measure_pick_errors(VulkanRunner& runner, const Material& material,
                                const ScenePlan& plan,
                                const std::vector<std::pair<std::string, SyntheticScene>>& views,
                                PickPlan& pick, const WaterGridDesc& grid) {
    // The gold as the scene's build would ship it: the fold is exact where the view obeys the
    // scene's facts, and a view that does not (a camera pitch outside the scene's range) then
    // shows every candidate and the gold folded alike.
    // A mesh gold is its exact surface (exact_surface_fragment).
    const Graph gold = pick.gold.choice("geometry") == "screen_pass"
                           ? fold_graph(material.compose(pick.gold).fragment, plan.facts).graph
                           : exact_surface_fragment(material, &plan, pick.gold);
    std::vector<ImageRGBA32F> references;
    for (const auto& [name, scene] : views) {
        const EvalResult d = evaluate_image(gold, "color", scene.eval_inputs(), scene.width,
                                            scene.height, EvalPrecision::Double);
        if (!d.ok()) return "the gold on the CPU (" + name + "): " + d.error;
        references.push_back(to_image(d, scene.width, scene.height));
    }
    for (PickCandidate& c : pick.candidates) {
        if (c.measured) continue;
        c.measured = true;
        const VariantBuild build = build_for_scene(material, plan, c.variant);
        if (!build.ok())
            return c.variant.key() + ": did not build: " +
                   (build.diagnostics.empty() ? std::string("?")
                                              : format_diagnostic(build.diagnostics.front()));
        for (size_t i = 0; i < views.size(); ++i) {
            const SyntheticScene& scene = views[i].second;
            RenderSettings settings{scene.width, scene.height, 0, false, false};
            settings.grid = grid; // a mesh candidate's
            const RenderResult r =
                runner.render(make_render_job(build.languages[0], scene, settings));
            if (!r.ok) return c.variant.key() + " (" + views[i].first + "): " + r.error;
            const ImageErrorStats e =
                compare_images(ImageRGBA32F{scene.width, scene.height, r.rgba}, references[i]);
            c.worst_de_p99 = std::max(c.worst_de_p99, e.ciede2000_p99);
            c.worst_max_abs = std::max(c.worst_max_abs, e.max_abs);
            c.nan_pixels += e.nan_inf_where_reference_finite;
        }
    }
    return "";
}

int cheapest_within(const std::vector<PickCandidate>& candidates, const PickBudget& budget) {
    int best = -1;
    for (size_t i = 0; i < candidates.size(); ++i) {
        const PickCandidate& c = candidates[i];
        if (!c.reached || !c.within(budget)) continue;
        if (best < 0) {
            best = int(i);
            continue;
        }
        const PickCandidate& b = candidates[size_t(best)];
        if (c.cost_per_pixel < b.cost_per_pixel ||
            (c.cost_per_pixel == b.cost_per_pixel && c.worst_de_p99 < b.worst_de_p99))
            best = int(i);
    }
    return best;
}

void add_axis_alternatives(PickPlan& pick, const Variant& chosen) {
    const auto& list = axes();
    for (size_t a = 0; a < list.size(); ++a) {
        if (chosen.choices[a] == pick.gold.choices[a]) continue;
        if (find_candidate(pick, chosen, list[a].name, pick.gold.choices[a])) continue;
        PickCandidate c;
        c.variant = chosen;
        c.variant.choices[a] = pick.gold.choices[a];
        c.relation = relation_to(c.variant, pick.gold);
        c.reached = false;
        pick.candidates.push_back(c);
    }
}

const PickCandidate* find_candidate(const PickPlan& pick, const Variant& base,
                                    const std::string& axis, const std::string& choice) {
    Variant want = base;
    if (!axis.empty() && set_choice(want, axis, choice)) return nullptr;
    for (const PickCandidate& c : pick.candidates)
        if (c.variant.key() == want.key()) return &c;
    return nullptr;
}

} // namespace watergen
