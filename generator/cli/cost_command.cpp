// `watergen cost`: the instructions lavapipe executes for one draw of a variant, counted by
// valgrind (draw_count.h). The command runs itself under valgrind as the worker (--counted).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <thread>

#include <valgrind/valgrind.h>

#include "commands.h"
#include "watergen/eval/draw/variant_render.h"
#include "watergen/eval/measure/draw_count.h"
#include "watergen/pipeline/variant_build.h"

namespace watergen::cli {

namespace {

struct CostOptions {
    Variant variant = default_variant();
    std::string preset, view = "beach";
    uint32_t size = 256, runs = 2;
    LoopUnroll unroll = LoopUnroll::AsHinted;
    bool counted = false;          // the worker, under valgrind
    std::vector<std::string> keys; // worker: these variants' GLSL paths instead of the variant's
    bool strict_half = false;      // half variants in explicit 16-bit types (EmitOptions)
    std::string scratch;
};

// Draws `lang` once more with the count on (RenderJob::counted_draw_label).
bool counted_render(VulkanRunner& runner, const LanguageBuild& lang, const SyntheticScene& scene,
                    const std::string& label, bool first_draw) {
    RenderJob job = make_render_job(lang, scene, {scene.width, scene.height, 0, false, false});
    job.counted_draw_label = label;
    job.count_first_draw = first_draw;
    const RenderResult r = runner.render(job);
    if (!r.ok) std::fprintf(stderr, "watergen: error: %s: %s\n", label.c_str(), r.error.c_str());
    return r.ok;
}

// The worker: builds the variant and draws each language path with the count on; or, given
// keys, each of those variants' GLSL path (draw_counted_keys).
int run_worker(const CostOptions& o, const Preset* preset, const Common& common) {
    if (!RUNNING_ON_VALGRIND) {
        std::fprintf(stderr, "watergen: error: --counted is the worker of watergen cost and runs "
                             "under valgrind --tool=callgrind\n");
        return kUsage;
    }
    const SyntheticScene scene = preset_scene(o.size, o.size, preset, o.view);
    auto build = [&](const Variant& v) {
        const bool strict = o.strict_half && v.choice("precision") == "half";
        return build_variant(v, preset, EmitOptions{strict, {}, o.unroll});
    };
    if (!o.keys.empty()) return draw_counted_keys(o.keys, scene, build, common);
    std::string cache;
    auto runner = create_runner(RunnerSetup{}, &cache);
    if (!runner) return kNoDevice;
    const VariantBuild b = build(o.variant);
    print_diagnostics(b.diagnostics, common);
    if (!b.ok()) return kFailed;
    const bool ok = counted_render(*runner, b.languages[0], scene, "glsl", true) &&
                    counted_render(*runner, b.languages[1], scene, "hlsl", true);
    return ok ? kOk : kFailed;
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
    if (o.strict_half) argv.push_back("--strict-half");
    return argv;
}

} // namespace

int draw_counted_keys(const std::vector<std::string>& keys, const SyntheticScene& scene,
                      const std::function<VariantBuild(const Variant&)>& build,
                      const Common& common) {
    std::string cache;
    auto runner = create_runner(RunnerSetup{}, &cache);
    if (!runner) return kNoDevice;
    std::map<std::string, int> seen; // a key given twice is labelled "<key>#2" (an A/A pair)
    for (const std::string& key : keys) {
        std::string error;
        const auto v = parse_variant_key(key, &error);
        if (!v) {
            std::fprintf(stderr, "watergen: error: --key: %s\n", error.c_str());
            return kUsage;
        }
        const VariantBuild b = build(*v);
        print_diagnostics(b.diagnostics, common);
        if (!b.ok()) return kFailed;
        const int n = ++seen[key];
        const std::string label = n == 1 ? key : key + "#" + std::to_string(n);
        if (!counted_render(*runner, b.languages[0], scene, label, false)) return kFailed;
    }
    return kOk;
}

std::optional<std::map<std::string, uint64_t>>
count_draw_costs(const std::vector<Variant>& variants, uint32_t size, const std::string& preset,
                 const std::string& view, std::string* error, bool strict_half) {
    std::vector<std::string> keys;
    for (const Variant& v : variants)
        keys.push_back(v.key());
    const KeyedWorker worker = [&](const std::vector<std::string>& part) {
        CostOptions o;
        o.size = size;
        o.preset = preset;
        o.view = view;
        o.strict_half = strict_half;
        o.keys = part;
        return worker_argv(o);
    };
    return count_keys_in_parallel(keys, worker, std::filesystem::temp_directory_path(),
                                  std::max(1u, std::thread::hardware_concurrency()), error);
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
    app.add_flag("--strict-half", o->strict_half,
                 "count a half variant written in explicit 16-bit types (as render --strict-half "
                 "draws it) instead of with mediump / min16float hints");
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
