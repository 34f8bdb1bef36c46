#include "watergen/plan/explain.h"

#include <fmt/format.h>

#include "watergen/ir/emit/emitter.h"

namespace watergen {

namespace {

MaterialOverview overview(const Material& m) {
    MaterialOverview o{m.name, m.file, count_variants(m.space), count_variants(full_space()),
                       "",     {}};
    for (size_t i = 0; i < axes().size(); ++i)
        if (m.space.choices[i].size() > 1)
            o.offered += fmt::format("{}{} {}", o.offered.empty() ? "" : " x ", axes()[i].name,
                                     m.space.choices[i].size());
    for (size_t i = builtin_rules().size(); i < m.space.rules.size(); ++i) {
        const Rule& r = m.space.rules[i];
        o.rules.push_back(fmt::format("{}={} {} {} in {{{}}}: {}{}", r.axis, r.choice,
                                      r.kind == Rule::Kind::Requires ? "requires" : "excludes",
                                      r.other_axis, fmt::join(r.other_choices, ", "), r.why,
                                      r.where.empty() ? "" : " [" + r.where + "]"));
    }
    return o;
}

// Hash of the folded shader's text without its key: equal for variants that fold alike.
std::string shape_of(const Graph& g) {
    Diagnostics ignored;
    return emit_fragment(g, Language::Glsl, "water.frag.glsl", "", ignored).source;
}

// What folding removed from one variant, one line per term, parameter and texture.
void count_removals(const FoldResult& r, const FoldFacts& facts,
                    std::map<std::string, size_t>& removals) {
    for (const auto& t : r.report.removed) {
        if (!t.named) continue;
        const FactSet fs =
            t.event >= 0 ? r.report.events[static_cast<size_t>(t.event)].facts : FactSet{};
        ++removals[fmt::format("removes term {} ({}): {}", t.name, t.origin,
                               describe_facts(facts, fs))];
    }
    for (const auto& p : r.report.removed_parameters)
        ++removals[fmt::format("no longer reads parameter {}: {}", p.name,
                               describe_facts(facts, p.facts))];
    for (const auto& p : r.report.removed_textures)
        ++removals[fmt::format("no longer reads texture {}: {}", p.name,
                               describe_facts(facts, p.facts))];
}

VariantRewrites rewrites_of(const std::string& key, const FoldResult& r, const FoldFacts& facts) {
    VariantRewrites d{key, r.report.live_before, r.report.live_after, {}};
    for (const auto& e : r.report.events)
        d.rewrites.push_back({e.origin, e.what, describe_facts(facts, e.facts)});
    return d;
}

SceneExplanation explain_scene(const Material& m, const ScenePlan& plan,
                               const std::string& detail_key, size_t sample) {
    SceneExplanation x;
    x.plan = &plan;
    const FoldFacts& facts = plan.facts;
    for (const auto& [name, fixed] : facts.fixed)
        x.fixes[name] = describe_facts(facts, FactSet().set(fixed.fact));
    for (const auto& [q, fixed] : facts.fixed_quantities)
        x.fixes[std::string(q.parameter.empty() ? q.id : q.parameter)] =
            describe_facts(facts, FactSet().set(fixed.fact));
    std::map<std::string, std::string> first_of_shape;
    // Folding takes a few milliseconds a variant: large spaces are explained from an evenly
    // spaced sample (the detailed variant always included).
    const size_t n = plan.variants.size();
    x.step = sample == 0 || n <= sample ? 1 : (n + sample - 1) / sample;
    for (size_t i = 0; i < n; ++i) {
        const Variant v = plan.variants[i];
        if (i % x.step != 0 && v.key() != detail_key) continue;
        const WaterShader shader = m.compose(v);
        if (has_errors(shader.fragment.diagnostics())) {
            ++x.uncomposable[shader.fragment.diagnostics().front().message];
            continue;
        }
        ++x.folded;
        const FoldResult r = fold_graph(shader.fragment, facts);
        x.live_before += r.report.live_before;
        x.live_after += r.report.live_after;
        auto [it, fresh] = first_of_shape.emplace(shape_of(r.graph), v.key());
        if (!fresh) x.same.push_back(v.key() + "\n      is the same shader as " + it->second);
        count_removals(r, facts, x.removals);
        if (v.key() == detail_key) x.detail = rewrites_of(v.key(), r, facts);
    }
    return x;
}

// Variants every plan skips, each scene's reason asked of scene_excludes again (as the plan
// did: the plans only count them). The first `listed` (0: all) of them into `out`; returns how
// many there are.
size_t unreached_variants(const Material& m, const std::vector<ScenePlan>& scenes, size_t listed,
                          std::vector<UnreachedVariant>& out) {
    std::vector<ParameterBounds> bounds;
    for (const ScenePlan& s : scenes)
        bounds.push_back(parameter_bounds(m, s.fixed));
    size_t count = 0;
    enumerate(m.space, [&](const Variant& v) {
        UnreachedVariant u;
        const bool kept = listed == 0 || out.size() < listed;
        for (size_t s = 0; s < scenes.size(); ++s) {
            std::optional<Exclusion> e = scene_excludes(scenes[s].scene, v, &bounds[s]);
            if (!e) return;
            if (kept) u.reasons.push_back({scenes[s].scene.name, SkippedGroup{*e, 0}.text()});
        }
        ++count;
        if (!kept) return;
        u.key = v.key();
        out.push_back(std::move(u));
    });
    return count;
}

} // namespace

Explanation explain_plans(const Material& m, const std::vector<ScenePlan>& scenes,
                          const std::string& detail_key, size_t sample, size_t listed) {
    Explanation e;
    e.material = overview(m);
    for (const ScenePlan& s : scenes)
        e.scenes.push_back(explain_scene(m, s, detail_key, sample));
    e.unreached_count = unreached_variants(m, scenes, listed, e.unreached);
    return e;
}

} // namespace watergen
