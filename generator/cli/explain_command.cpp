// watergen explain [MATERIAL] [--scene S ...]: per scene, the variants it skips and the terms
// it folds away, each with the scene fact (file:line:column and JSON path) behind it; then the
// variants no scene reaches. Nothing is compiled: composing and folding take milliseconds.
#include <cstdio>
#include <map>

#include <fmt/format.h>

#include "commands.h"
#include "watergen/pipeline/build_output.h"
#include "watergen/ir/emitter.h"

namespace watergen::cli {

namespace {

void print_material(const Material& m, size_t count) {
    std::string offered;
    for (size_t i = 0; i < axes().size(); ++i)
        if (m.space.choices[i].size() > 1)
            offered += fmt::format("{}{} {}", offered.empty() ? "" : " x ", axes()[i].name, m.space.choices[i].size());
    std::printf("material %s%s: %zu variants (%s; of %zu in the full space)\n", m.name.c_str(),
                m.file.empty() ? " (built in)" : (" (" + m.file + ")").c_str(), count,
                offered.empty() ? "one choice per axis" : offered.c_str(), count_variants(full_space()));
    for (size_t i = builtin_rules().size(); i < m.space.rules.size(); ++i) {
        const Rule& r = m.space.rules[i];
        std::printf("  rule: %s=%s %s %s in {%s}: %s%s\n", r.axis.c_str(), r.choice.c_str(),
                    r.kind == Rule::Kind::Requires ? "requires" : "excludes", r.other_axis.c_str(),
                    fmt::format("{}", fmt::join(r.other_choices, ", ")).c_str(), r.why.c_str(),
                    r.where.empty() ? "" : (" [" + r.where + "]").c_str());
    }
}

// Hash of the folded shader's text without its key: equal for variants that fold alike.
std::string shape_of(const Graph& g) {
    Diagnostics ignored;
    return emit_fragment(g, Language::Glsl, "water.frag.glsl", "", ignored).source;
}

void explain_scene(const Material& m, const ScenePlan& plan, const std::string& detail_key, size_t sample) {
    const SceneFacts& s = plan.scene;
    std::printf("\nscene %s (%s): reaches %zu of %zu variants\n", s.name.c_str(), s.file.c_str(), plan.variants.size(),
                plan.variants.size() + plan.skipped);
    std::map<std::string, size_t> skips;
    enumerate(m.space, [&](const Variant& v) {
        if (auto e = scene_excludes(s, v))
            ++skips[fmt::format("{}={}: {} [{}]", e->axis, e->choice, e->reason, e->where)];
    });
    for (const auto& [why, n] : skips) std::printf("  skips %zu variant%s with %s\n", n, n == 1 ? "" : "s", why.c_str());
    for (const auto& [name, fixed] : plan.facts.fixed)
        std::printf("  fixes %s: %s\n", name.c_str(), describe_facts(plan.facts, FactSet().set(fixed.fact)).c_str());
    std::string targets;
    for (Target t : plan.targets) targets += (targets.empty() ? "" : ", ") + std::string(to_string(t));
    std::printf("  emits %s (platforms %s)\n", targets.c_str(), fmt::format("{}", fmt::join(s.platforms, ", ")).c_str());

    std::map<std::string, size_t> removals, uncomposable;
    std::map<std::string, std::string> first_of_shape;
    std::vector<std::string> same;
    size_t before = 0, after = 0, folded = 0;
    // Folding takes a few milliseconds a variant: large spaces are explained from an evenly
    // spaced sample (the detailed variant always included).
    const size_t n = plan.variants.size();
    const size_t step = sample == 0 || n <= sample ? 1 : (n + sample - 1) / sample;
    for (size_t i = 0; i < n; ++i) {
        const Variant& v = plan.variants[i];
        if (i % step != 0 && v.key() != detail_key) continue;
        const WaterShader shader = m.compose(v);
        if (has_errors(shader.fragment.diagnostics())) {
            ++uncomposable[shader.fragment.diagnostics().front().message];
            continue;
        }
        ++folded;
        const FoldResult r = fold_graph(shader.fragment, plan.facts);
        before += r.report.live_before;
        after += r.report.live_after;
        auto [it, fresh] = first_of_shape.emplace(shape_of(r.graph), v.key());
        if (!fresh) same.push_back(v.key() + "\n      is the same shader as " + it->second);
        for (const auto& t : r.report.removed) {
            if (!t.named) continue;
            const FactSet fs = t.event >= 0 ? r.report.events[static_cast<size_t>(t.event)].facts : FactSet{};
            ++removals[fmt::format("removes term {} ({}): {}", t.name, t.origin, describe_facts(plan.facts, fs))];
        }
        for (const auto& p : r.report.removed_parameters)
            ++removals[fmt::format("no longer reads parameter {}: {}", p.name, describe_facts(plan.facts, p.facts))];
        for (const auto& p : r.report.removed_textures)
            ++removals[fmt::format("no longer reads texture {}: {}", p.name, describe_facts(plan.facts, p.facts))];
        if (v.key() == detail_key) {
            std::printf("  %s: %zu -> %zu live IR nodes; rewrites:\n", v.key().c_str(), r.report.live_before, r.report.live_after);
            for (const auto& e : r.report.events)
                std::printf("    %s: %s\n      because %s\n", e.origin.c_str(), e.what.c_str(), describe_facts(plan.facts, e.facts).c_str());
        }
    }
    if (folded < n) std::printf("  folded %zu of its %zu variants (every %zu-th; --sample 0 folds all)\n", folded, n, step);
    for (const auto& [line, k] : removals) std::printf("  in %zu of %zu variants %s\n", k, folded, line.c_str());
    for (const auto& line : same) std::printf("  after folding %s\n", line.c_str());
    for (const auto& [why, k] : uncomposable)
        std::printf("  %zu variant%s do not compose yet: %s\n", k, k == 1 ? "" : "s", why.c_str());
    std::printf("  live IR nodes over the folded variants: %zu -> %zu\n", before, after);
}

} // namespace

Runner add_explain_command(CLI::App& app, const Common& common) {
    struct Options {
        std::string material;
        std::vector<std::string> scenes;
        std::string variant;
        size_t limit = 20;
        size_t sample = 200;
    };
    auto o = std::make_shared<Options>();
    app.add_option("material", o->material, "material description (default: the built-in default material)");
    app.add_option("--scene", o->scenes, "scene description (repeatable)")->required();
    app.add_option("--variant", o->variant, "also list every rewrite of this variant (a key, axis=choice,...), per scene");
    app.add_option("--sample", o->sample, "fold at most this many variants per scene, evenly spaced (default 200; 0: all)");
    app.add_option("--limit", o->limit, "variants no scene reaches to list one by one (default 20; 0 lists all)");
    return [o, &common]() {
        Material m;
        std::vector<SceneFacts> scenes;
        if (!load_material_and_scenes(o->material, o->scenes, m, scenes, common)) return kUsage;
        std::string detail;
        if (!o->variant.empty()) {
            std::string error;
            const auto v = parse_variant_key(o->variant, &error);
            if (!v) {
                std::fprintf(stderr, "watergen: error: --variant: %s\n", error.c_str());
                return kUsage;
            }
            detail = v->key();
        }
        Diagnostics ds;
        auto plan = plan_build(m, scenes, ds);
        if (!plan) {
            print_diagnostics(ds, common);
            return kUsage;
        }
        print_material(m, count_variants(m.space));
        for (const auto& s : plan->scenes) explain_scene(m, s, detail, o->sample);

        // Variants no scene reaches, each with every scene's reason.
        std::vector<std::string> lines;
        enumerate(m.space, [&](const Variant& v) {
            std::string why;
            for (const auto& s : plan->scenes) {
                auto e = scene_excludes(s.scene, v);
                if (!e) return;
                why += fmt::format("\n    {}: {}={}: {} [{}]", s.scene.name, e->axis, e->choice, e->reason, e->where);
            }
            lines.push_back(v.key() + why);
        });
        std::printf("\nnot generated: %zu variant%s no scene reaches\n", lines.size(), lines.size() == 1 ? "" : "s");
        for (size_t i = 0; i < lines.size() && (o->limit == 0 || i < o->limit); ++i) std::printf("  %s\n", lines[i].c_str());
        if (o->limit != 0 && lines.size() > o->limit)
            std::printf("  ... and %zu more (--limit 0 lists all)\n", lines.size() - o->limit);
        return kOk;
    };
}

} // namespace watergen::cli
