#include "watergen/eval/measure/cost_worker.h"

#include <functional>
#include <map>

#include <fmt/format.h>
#include <valgrind/valgrind.h>

#include "watergen/eval/draw/variant_render.h"
#include "watergen/eval/scene/scene_conform.h"
#include "watergen/pipeline/build/build_output.h"

namespace watergen {

namespace {

using Build = std::function<VariantBuild(const Variant&)>;

// Refuses a worker run outside valgrind: the brackets would count nothing.
bool under_valgrind(const char* command, CountWorkerRun& run) {
    if (RUNNING_ON_VALGRIND) return true;
    run.error = std::string("--counted is the worker of watergen ") + command +
                " and runs under valgrind --tool=callgrind";
    run.status = RunStatus::BadInput;
    return false;
}

std::unique_ptr<VulkanRunner> open_device(CountWorkerRun& run) {
    std::string cache;
    auto runner = open_draw_device({}, &cache, &run.error);
    if (!runner) run.status = RunStatus::NoDevice;
    return runner;
}

// Draws `lang` once more with the count on (RenderJob::counted_draw_label).
// A mesh variant is drawn over `mesh`'s grid (RenderSettings::grid and tess_max).
bool counted_draw(VulkanRunner& runner, const LanguageBuild& lang, const SyntheticScene& scene,
                  const std::string& label, bool first_draw, CountWorkerRun& run,
                  const RenderSettings& mesh = {}) {
    RenderSettings settings = mesh;
    settings.width = scene.width;
    settings.height = scene.height;
    settings.timed_draws = 0;
    settings.cpu_double = settings.cpu_float = false;
    RenderJob job = make_render_job(lang, scene, settings);
    job.counted_draw_label = label;
    job.count_first_draw = first_draw;
    const RenderResult r = runner.render(job);
    if (r.ok) return true;
    run.error = label + ": " + r.error;
    run.status = RunStatus::Failed;
    return false;
}

// Keeps a build's diagnostics; false (the run failed) when it did not build.
bool built(const VariantBuild& b, CountWorkerRun& run) {
    run.diagnostics.insert(run.diagnostics.end(), b.diagnostics.begin(), b.diagnostics.end());
    if (!b.ok()) run.status = RunStatus::Failed;
    return b.ok();
}

// Each key's variant built with `build`, its GLSL path drawn over `scene` once with the steady
// draw counted, labelled with the key ("<key>#2" for its second occurrence).
CountWorkerRun draw_counted_keys(const std::vector<std::string>& keys, const SyntheticScene& scene,
                                 const Build& build, const RenderSettings& mesh = {}) {
    CountWorkerRun run;
    auto runner = open_device(run);
    if (!runner) return run;
    std::map<std::string, int> seen;
    for (const std::string& key : keys) {
        std::string error;
        const auto v = parse_variant_key(key, &error);
        if (!v) {
            run.error = "--key: " + error;
            run.status = RunStatus::BadInput;
            return run;
        }
        const VariantBuild b = build(*v);
        if (!built(b, run)) return run;
        const int n = ++seen[key];
        const std::string label = n == 1 ? key : key + "#" + std::to_string(n);
        if (!counted_draw(*runner, b.languages[0], scene, label, false, run, mesh)) return run;
    }
    return run;
}

} // namespace

std::filesystem::path own_executable() {
    return std::filesystem::read_symlink("/proc/self/exe");
}

std::vector<std::string> count_worker_argv(const VariantCountJob& job,
                                           const std::filesystem::path& executable) {
    std::vector<std::string> argv = {executable.string(), "cost", "--counted", "--size",
                                     std::to_string(job.size)};
    const auto& list = axes();
    for (size_t i = 0; i < list.size(); ++i)
        argv.insert(argv.end(), {"--" + list[i].name, job.variant.choices[i]});
    for (const std::string& key : job.keys)
        argv.insert(argv.end(), {"--key", key});
    if (!job.preset.empty()) argv.insert(argv.end(), {"--preset", job.preset});
    argv.insert(argv.end(), {"--view", job.view});
    argv.insert(argv.end(), {"--unroll", to_string(job.unroll)});
    if (job.strict_half) argv.push_back("--strict-half");
    argv.insert(argv.end(), {"--grid-spacing", fmt::format("{}", job.grid.spacing), "--grid-rings",
                             std::to_string(job.grid.ring_cells), "--grid-levels",
                             std::to_string(job.grid.levels)});
    if (job.tess_max > 0) argv.insert(argv.end(), {"--tess-max", fmt::format("{}", job.tess_max)});
    return argv;
}

std::vector<std::string> count_worker_argv(const MaterialCountJob& job,
                                           const std::filesystem::path& executable) {
    std::vector<std::string> argv = {executable.string(), "pick"};
    // The material first: --scene takes every word up to the next flag (`--scene
    // examples/scenes/*.json`), so a material after it would be read as a second scene.
    if (!job.material_path.empty())
        argv.push_back(std::filesystem::absolute(job.material_path).string());
    argv.insert(argv.end(), {"--counted", "--cost-size", std::to_string(job.size)});
    if (!job.folded) argv.push_back("--unfolded");
    for (const std::string& key : job.keys)
        argv.insert(argv.end(), {"--key", key});
    argv.insert(argv.end(), {"--grid-spacing", fmt::format("{}", job.grid.spacing), "--grid-rings",
                             std::to_string(job.grid.ring_cells), "--grid-levels",
                             std::to_string(job.grid.levels)});
    if (!job.scene_path.empty())
        argv.insert(argv.end(), {"--scene", std::filesystem::absolute(job.scene_path).string()});
    return argv;
}

CountWorkerRun run_count_worker(const VariantCountJob& job) {
    CountWorkerRun run;
    if (!under_valgrind("cost", run)) return run;
    const Preset* preset = job.preset.empty() ? nullptr : find_preset(job.preset);
    const SyntheticScene scene = preset_scene(job.size, job.size, preset, job.view);
    const Build build = [&](const Variant& v) {
        const bool strict = job.strict_half && v.choice("precision") == "half";
        return build_variant(v, preset, EmitOptions{strict, {}, job.unroll});
    };
    RenderSettings mesh;
    mesh.grid = job.grid;
    mesh.tess_max = job.tess_max;
    if (!job.keys.empty()) return draw_counted_keys(job.keys, scene, build, mesh);
    auto runner = open_device(run);
    if (!runner) return run;
    const VariantBuild b = build(job.variant);
    if (!built(b, run)) return run;
    if (counted_draw(*runner, b.languages[0], scene, "glsl", true, run, mesh))
        counted_draw(*runner, b.languages[1], scene, "hlsl", true, run, mesh);
    return run;
}

CountWorkerRun run_count_worker(const MaterialCountJob& job, const Material& material,
                                const ScenePlan* plan) {
    CountWorkerRun run;
    if (!under_valgrind("pick", run)) return run;
    const SyntheticScene base = make_synthetic_scene(job.size, job.size);
    const SyntheticScene scene = plan ? conform_scene(base, *plan, material) : base;
    RenderSettings mesh;
    mesh.grid = job.grid;
    return draw_counted_keys(
        job.keys, scene,
        [&](const Variant& v) {
            return plan && job.folded ? build_for_scene(material, *plan, v)
                                      : build_shader(material.compose(v));
        },
        mesh);
}

} // namespace watergen
