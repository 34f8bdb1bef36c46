// watergen explain [MATERIAL] [--scene S ...]: per scene, the variants it skips and the terms
// it folds away, each with the scene fact (file:line:column and JSON path) behind it; then the
// variants no scene reaches. The work is explain_build() (pipeline/build_explain.h); this
// prints it.
#include <cstdio>

#include <fmt/format.h>

#include "commands.h"
#include "watergen/ir/core/text.h"
#include "watergen/pipeline/build/build_explain.h"

namespace watergen::cli {

namespace {

void print_material(const MaterialOverview& m) {
    std::printf("material %s%s: %zu variants (%s; of %zu in the full space)\n", m.name.c_str(),
                m.file.empty() ? " (built in)" : (" (" + m.file + ")").c_str(), m.variants,
                m.offered.empty() ? "one choice per axis" : m.offered.c_str(), m.full_space);
    for (const auto& rule : m.rules)
        std::printf("  rule: %s\n", rule.c_str());
}

void print_scene(const SceneExplanation& x) {
    const ScenePlan& plan = *x.plan;
    const SceneFacts& s = plan.scene;
    std::printf("\nscene %s (%s): reaches %zu of %zu variants\n", s.name.c_str(), s.file.c_str(),
                plan.variants.size(), plan.variants.size() + plan.skipped);
    for (const auto& g : plan.skipped_groups)
        std::printf("  skips %zu variant%s with %s\n", g.variants, g.variants == 1 ? "" : "s",
                    g.text().c_str());
    for (const auto& [name, because] : x.fixes)
        std::printf("  fixes %s: %s\n", name.c_str(), because.c_str());
    const std::string targets =
        join(plan.targets, [](Target t) { return std::string(to_string(t)); });
    std::printf("  emits %s (platforms %s)\n", targets.c_str(),
                fmt::format("{}", fmt::join(s.platforms, ", ")).c_str());
    if (x.detail) {
        std::printf("  %s: %zu -> %zu live IR nodes; rewrites:\n", x.detail->key.c_str(),
                    x.detail->live_before, x.detail->live_after);
        for (const auto& r : x.detail->rewrites)
            std::printf("    %s: %s\n      because %s\n", r.origin.c_str(), r.what.c_str(),
                        r.because.c_str());
    }
    const size_t n = plan.variants.size();
    if (x.folded < n)
        std::printf("  folded %zu of its %zu variants (every %zu-th; --sample 0 folds all)\n",
                    x.folded, n, x.step);
    for (const auto& [line, k] : x.removals)
        std::printf("  in %zu of %zu variants %s\n", k, x.folded, line.c_str());
    for (const auto& line : x.same)
        std::printf("  after folding %s\n", line.c_str());
    for (const auto& [why, k] : x.uncomposable)
        std::printf("  %zu variant%s do not compose yet: %s\n", k, k == 1 ? "" : "s", why.c_str());
    std::printf("  live IR nodes over the folded variants: %zu -> %zu\n", x.live_before,
                x.live_after);
}

void print_unreached(const std::vector<UnreachedVariant>& unreached, size_t count, size_t limit) {
    std::printf("\nnot generated: %zu variant%s no scene reaches\n", count, count == 1 ? "" : "s");
    for (size_t i = 0; i < unreached.size() && (limit == 0 || i < limit); ++i) {
        std::string line = unreached[i].key;
        for (const auto& [scene, why] : unreached[i].reasons)
            line += "\n    " + scene + ": " + why;
        std::printf("  %s\n", line.c_str());
    }
    if (limit != 0 && count > limit)
        std::printf("  ... and %zu more (--limit 0 lists all)\n", count - limit);
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
    app.add_option("material", o->material,
                   "material description (default: the built-in default material)");
    app.add_option("--scene", o->scenes, "scene description (repeatable)")->required();
    app.add_option("--variant", o->variant,
                   "also list every rewrite of this variant (a key, axis=choice,...), per scene");
    app.add_option(
        "--sample", o->sample,
        "fold at most this many variants per scene, evenly spaced (default 200; 0: all)");
    app.add_option("--limit", o->limit,
                   "variants no scene reaches to list one by one (default 20; 0 lists all)");
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
        const auto explained = explain_build(m, scenes, detail, o->sample, o->limit, ds);
        if (!explained) return stop(ds, "", RunStatus::BadInput, common);
        const Explanation& e = explained->explanation;
        print_material(e.material);
        for (const auto& scene : e.scenes)
            print_scene(scene);
        print_unreached(e.unreached, e.unreached_count, o->limit);
        return kOk;
    };
}

} // namespace watergen::cli
