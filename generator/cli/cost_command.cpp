// `watergen cost`: the instructions lavapipe executes for one draw of a variant, counted by
// valgrind (draw_count.h). The command runs itself under valgrind as the worker (--counted).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>

#include <valgrind/valgrind.h>

#include "commands.h"
#include "watergen/pipeline/variant_build.h"
#include "watergen/render/draw_count.h"
#include "watergen/render/variant_render.h"

namespace watergen::cli {

namespace {

struct CostOptions {
    Variant variant = default_variant();
    std::string preset, view = "beach";
    uint32_t size = 256, runs = 2;
    LoopUnroll unroll = LoopUnroll::AsHinted;
    bool counted = false;          // the worker, under valgrind
    std::vector<std::string> keys; // worker: these variants' GLSL paths instead of the variant's
    std::string scratch;
};

// Draws `lang` once more with the count on (RenderJob::counted_draw_label).
bool counted_render(VulkanRunner& runner, const LanguageBuild& lang, const SyntheticScene& scene,
                    uint32_t size, const std::string& label) {
    RenderJob job = make_render_job(lang, scene, {size, size, 0, false, false});
    job.counted_draw_label = label;
    const RenderResult r = runner.render(job);
    if (!r.ok) std::fprintf(stderr, "watergen: error: %s: %s\n", label.c_str(), r.error.c_str());
    return r.ok;
}

// The worker: builds the variant and draws each language path with the count on; or, given
// keys, each of those variants' GLSL path, labelled with its key.
int run_worker(const CostOptions& o, const Preset* preset, const Common& common) {
    if (!RUNNING_ON_VALGRIND) {
        std::fprintf(stderr, "watergen: error: --counted is the worker of watergen cost and runs "
                             "under valgrind --tool=callgrind\n");
        return kUsage;
    }
    std::vector<Variant> variants = {o.variant};
    if (!o.keys.empty()) variants.clear();
    for (const std::string& key : o.keys) {
        std::string error;
        const auto v = parse_variant_key(key, &error);
        if (!v) {
            std::fprintf(stderr, "watergen: error: --key: %s\n", error.c_str());
            return kUsage;
        }
        variants.push_back(*v);
    }
    std::string cache;
    auto runner = create_runner(RunnerSetup{}, &cache);
    if (!runner) return kNoDevice;
    const SyntheticScene scene = preset_scene(o.size, o.size, preset, o.view);
    std::map<std::string, int> seen; // a variant given twice is labelled "<key>#2" (an A/A pair)
    for (const Variant& v : variants) {
        const int n = ++seen[v.key()];
        const std::string label = n == 1 ? v.key() : v.key() + "#" + std::to_string(n);
        const VariantBuild build = build_variant(v, preset, EmitOptions{false, {}, o.unroll});
        print_diagnostics(build.diagnostics, common);
        if (!build.ok()) return kFailed;
        const bool ok = o.keys.empty()
                            ? counted_render(*runner, build.languages[0], scene, o.size, "glsl") &&
                                  counted_render(*runner, build.languages[1], scene, o.size, "hlsl")
                            : counted_render(*runner, build.languages[0], scene, o.size, label);
        if (!ok) return kFailed;
    }
    return kOk;
}

std::vector<std::string> worker_argv(const CostOptions& o) {
    std::vector<std::string> argv = {std::filesystem::read_symlink("/proc/self/exe").string(),
                                     "cost", "--counted", "--size", std::to_string(o.size)};
    const auto& list = axes();
    for (size_t i = 0; i < list.size(); ++i) {
        argv.push_back("--" + list[i].name);
        argv.push_back(o.variant.choices[i]);
    }
    for (const std::string& key : o.keys)
        argv.insert(argv.end(), {"--key", key});
    if (!o.preset.empty()) argv.insert(argv.end(), {"--preset", o.preset});
    argv.insert(argv.end(), {"--view", o.view});
    argv.insert(argv.end(), {"--unroll", to_string(o.unroll)});
    return argv;
}

} // namespace

std::optional<std::map<std::string, uint64_t>>
count_draw_costs(const std::vector<Variant>& variants, uint32_t size, const std::string& preset,
                 const std::string& view, std::string* error) {
    CostOptions o;
    o.size = size;
    o.preset = preset;
    o.view = view;
    for (const Variant& v : variants)
        o.keys.push_back(v.key());
    return steady_draw_counts(
        count_draws_under_valgrind(worker_argv(o), std::filesystem::temp_directory_path()), error);
}

Runner add_cost_command(CLI::App& app, const Common& common) {
    auto o = std::make_shared<CostOptions>();
    add_variant_options(app, o->variant, o->preset);
    app.add_option("--size", o->size, "image width and height (default 256)")
        ->check(CLI::Range(8, 2048));
    app.add_option("--runs", o->runs,
                   "valgrind runs; more than one shows the count repeats (default 2)")
        ->check(CLI::Range(1, 20));
    add_unroll_option(app, o->unroll);
    add_view_option(app, o->view);
    app.add_option("--scratch", o->scratch,
                   "directory under which each valgrind run keeps its dumps in a directory of "
                   "its own, removed afterwards (default: the system's temporary directory)");
    app.add_flag("--counted", o->counted, "")->group(""); // the worker; hidden
    app.add_option("--key", o->keys, "")->group("");      // the worker's variants; hidden
    return [o, &common]() {
        const Preset* preset = nullptr;
        if (!resolve_variant(o->variant, o->preset, &preset)) return kUsage;
        if (o->counted) return run_worker(*o, preset, common);
        const std::filesystem::path scratch = o->scratch.empty()
                                                  ? std::filesystem::temp_directory_path()
                                                  : std::filesystem::path(o->scratch);
        std::map<std::string, std::vector<uint64_t>> counts;
        for (uint32_t run = 0; run < o->runs; ++run) {
            const DrawCountRun r = count_draws_under_valgrind(worker_argv(*o), scratch);
            if (!r.ok()) {
                std::fprintf(stderr, "watergen: error: %s\n", r.error.c_str());
                return kFailed;
            }
            for (const auto& c : r.counts)
                counts[c.label].push_back(c.instructions);
        }
        std::printf("%s\ninstructions lavapipe executes (valgrind callgrind), %u run(s): one "
                    "%ux%u draw in view %s, and pipeline creation through the first draw (the "
                    "JIT):\n",
                    o->variant.key().c_str(), o->runs, o->size, o->size, o->view.c_str());
        // The smallest count of a span, and by how much the runs differ (percent).
        auto spread = [](const std::vector<uint64_t>& v) {
            const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
            const double d = static_cast<double>(*hi - *lo);
            return std::pair{*lo, *lo ? 100.0 * d / static_cast<double>(*lo) : 0.0};
        };
        for (const char* path : {"glsl", "hlsl"}) {
            if (counts[path].empty() || counts[std::string(path) + " first"].empty()) {
                std::fprintf(stderr, "watergen: error: valgrind gave no count of the %s path\n",
                             path);
                return kFailed;
            }
            const auto [draw, draw_spread] = spread(counts[path]);
            const auto [first, first_spread] = spread(counts[std::string(path) + " first"]);
            std::printf("  %-5s %14llu  %9.1f per pixel  runs differ by %.4f%%   first draw "
                        "%14llu  runs differ by %.4f%%\n",
                        path, static_cast<unsigned long long>(draw),
                        static_cast<double>(draw) / (double(o->size) * o->size), draw_spread,
                        static_cast<unsigned long long>(first), first_spread);
        }
        return kOk;
    };
}

} // namespace watergen::cli
