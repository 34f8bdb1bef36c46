#include "watergen/eval/bench/modes_bench.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "watergen/eval/draw/variant_render.h"
#include "watergen/eval/measure/gpu_cost.h"
#include "watergen/eval/measure/interleaved_timing.h"
#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/toolchain/spirv_tools_stage.h"

namespace watergen {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// What one variant is drawn from in one mode: a built shader, the selector values, and (frozen)
// the variant's own fragment modules.
struct Draw {
    const VariantBuild* build = nullptr;
    std::map<std::string, double> selectors;
    std::array<std::vector<uint32_t>, 2> frozen;
};

struct Mode {
    std::vector<ShaderChoices> shaders;
    std::vector<VariantBuild> builds;
};

// Composes and compiles every shader of `mode`; the time it took, or -1 with `error` set.
double build_mode(const Material& m, const std::vector<Variant>& all, BuildMode mode, Mode& out,
                  std::string& error) {
    out.shaders = shaders_for(all, mode);
    const auto t0 = Clock::now();
    for (const ShaderChoices& s : out.shaders) {
        out.builds.push_back(build_shader(m.compose(s)));
        if (!out.builds.back().ok()) {
            error = s.key() +
                    " did not build: " + format_diagnostic(out.builds.back().diagnostics.front());
            return -1;
        }
    }
    return ms_since(t0);
}

size_t fragment_bytes(const VariantBuild& b) {
    return b.languages[0].fragment.toolchain.spirv_optimized.size() * sizeof(uint32_t);
}

Draw draw_of(const Mode& mode, const Variant& v) {
    for (size_t i = 0; i < mode.shaders.size(); ++i)
        if (mode.shaders[i].covers(v))
            return {&mode.builds[i], mode.shaders[i].selector_values(v), {}};
    return {};
}

// The variant's fragment modules of both language paths with the selectors frozen.
bool freeze(Draw& d, std::string& error) {
    for (size_t lang = 0; lang < 2; ++lang) {
        const StageBuild& frag = d.build->languages[lang].fragment;
        std::map<std::string, std::vector<double>> values;
        for (const auto& [name, value] : d.selectors)
            values[name] = {value};
        const OptimizeResult r = freeze_specialization(
            frag.toolchain.spirv_optimized,
            specialization_values(frag.source.interface.specialization, values),
            frag.source.file_name);
        if (r.spirv.empty()) {
            error = "freezing failed: " +
                    (r.diagnostics.empty() ? "?" : format_diagnostic(r.diagnostics.front()));
            return false;
        }
        d.frozen[lang] = r.spirv;
    }
    return true;
}

RenderResult render_draw(VulkanRunner& runner, const Draw& d, size_t lang,
                         const SyntheticScene& scene, const RenderSettings& settings) {
    SyntheticScene selected = scene;
    for (const auto& [name, value] : d.selectors)
        selected.uniforms[name] = {value};
    RenderJob job = make_render_job(d.build->languages[lang], selected, settings);
    if (!d.frozen[lang].empty()) {
        job.fragment_spirv = d.frozen[lang];
        job.specialization.clear();
    }
    return runner.render(job);
}

// The variants rendered: `count` spread evenly over the sorted list (0: all).
std::vector<Variant> spread(const std::vector<Variant>& all, size_t count) {
    if (count == 0 || count >= all.size()) return all;
    std::vector<Variant> out;
    for (size_t i = 0; i < count; ++i)
        out.push_back(all[i * (all.size() - 1) / std::max<size_t>(count - 1, 1)]);
    return out;
}

// Renders every sampled variant in every mode, `rounds` times, the modes interleaved (each
// round starts with another mode); the first round renders both language paths and keeps the
// images, which are held against the permutation's.
void measure_modes(VulkanRunner& runner, const std::vector<Variant>& sample,
                   const std::vector<std::array<Draw, 5>>& draws, const ModesBenchOptions& o,
                   ModesBenchResult& out) {
    const SyntheticScene scene = make_synthetic_scene(o.size, o.size);
    const RenderSettings settings{o.size, o.size, o.draws, false, false};
    const size_t modes = out.rows.size();
    using Times = std::array<std::vector<double>, 3>; // pipeline, first draw, steady
    std::vector<std::vector<Times>> t(modes, std::vector<Times>(sample.size()));
    std::vector<std::vector<std::array<ImageRGBA32F, 2>>> images(
        modes, std::vector<std::array<ImageRGBA32F, 2>>(sample.size()));
    for (unsigned round = 0; round < std::max(1u, o.rounds); ++round)
        for (size_t i = 0; i < sample.size(); ++i)
            for (size_t j = 0; j < modes; ++j) {
                const size_t k = (j + round) % modes;
                for (size_t lang = 0; lang < (round == 0 ? 2u : 1u); ++lang) {
                    const RenderResult r = render_draw(runner, draws[i][k], lang, scene, settings);
                    if (!r.ok) {
                        out.error = out.rows[k].mode + " " + sample[i].key() + ": " + r.error;
                        return;
                    }
                    if (lang == 0)
                        for (auto [list, v] :
                             {std::pair{0, r.pipeline_ms}, std::pair{1, r.first_draw_ms},
                              std::pair{2, r.steady_draw_ms}})
                            t[k][i][static_cast<size_t>(list)].push_back(v);
                    if (round == 0) images[k][i][lang] = ImageRGBA32F{o.size, o.size, r.rgba};
                }
            }
    for (size_t k = 0; k < modes; ++k) {
        ModeRow& row = out.rows[k];
        Times every;
        for (size_t i = 0; i < sample.size(); ++i) {
            ModeVariantTimes v{sample[i].key(), median(t[k][i][0]), median(t[k][i][1]),
                               median(t[k][i][2]), 0};
            for (size_t lang = 0; lang < 2; ++lang) {
                const ImageErrorStats d = compare_images(images[k][i][lang], images[0][i][lang]);
                if (!d.error.empty() || d.nan_inf_pixels != d.reference_nan_inf_pixels)
                    out.error = row.mode + " " + sample[i].key() + ": images cannot be compared";
                v.max_abs = std::max(v.max_abs, d.max_abs);
            }
            row.max_abs = std::max(row.max_abs, v.max_abs);
            for (size_t q = 0; q < 3; ++q)
                every[q].insert(every[q].end(), t[k][i][q].begin(), t[k][i][q].end());
            row.variants.push_back(v);
        }
        row.pipeline_ms = median(every[0]);
        row.first_draw_ms = median(every[1]);
        row.steady_ms = median(every[2]);
    }
}

// The pipeline of `d` for ACO (GLSL path): as render_draw makes it, the scene's uniforms and the
// selectors giving the specialization constants, a frozen fragment module in its place.
AcoPipelineSource aco_draw(const Draw& d, const SyntheticScene& scene, const std::string& name) {
    SyntheticScene selected = scene;
    for (const auto& [n, value] : d.selectors)
        selected.uniforms[n] = {value};
    const LanguageBuild& glsl = d.build->languages[0];
    AcoPipelineSource s = aco_source(
        glsl, name,
        specialization_values(glsl.fragment.source.interface.specialization, selected.uniforms));
    if (!d.frozen[0].empty()) {
        s.fragment = d.frozen[0];
        s.specialization.clear();
    }
    return s;
}

// Every rendered variant's pipeline in every mode on each AMD family: medians per mode.
void add_mode_gpu_costs(const std::vector<Variant>& sample,
                        const std::vector<std::array<Draw, 5>>& draws, const ModesBenchOptions& o,
                        ModesBenchResult& out) {
    const SyntheticScene scene = make_synthetic_scene(o.size, o.size);
    std::vector<AcoPipelineSource> sources;
    std::vector<std::vector<EmittedLoop>> loops;
    for (size_t k = 0; k < out.rows.size(); ++k)
        for (size_t i = 0; i < sample.size(); ++i) {
            sources.push_back(
                aco_draw(draws[i][k], scene, out.rows[k].mode + " " + sample[i].key()));
            loops.push_back(emitted_loops(draws[i][k].build->shader.fragment));
        }
    const auto runs =
        compile_on_targets(o.gpu_targets, sources, std::filesystem::temp_directory_path(),
                           std::max(1u, std::thread::hardware_concurrency()));
    for (const AcoTargetRun& run : runs) {
        if (!run.ok()) {
            out.error = run.error;
            return;
        }
        out.targets.push_back(run.target.name);
        for (size_t k = 0; k < out.rows.size(); ++k) {
            std::array<std::vector<double>, 7> values;
            ModeTargetCost c;
            c.waves_min = INFINITY;
            for (size_t i = 0; i < sample.size(); ++i) {
                const size_t at = k * sample.size() + i;
                const PipelineGpuCost cost = gpu_cost(run.pipelines[at], loops[at]);
                const StageGpuCost* f = cost.stage("fragment");
                if (!cost.ok() || !f) {
                    out.error = run.target.name + ": " + cost.name + ": " + cost.error;
                    return;
                }
                const double v[7] = {f->instructions,
                                     cost.fragment_cost(),
                                     f->vgprs,
                                     f->sgprs,
                                     f->waves_per_simd,
                                     f->code_bytes,
                                     f->spilled_vgprs + f->spilled_sgprs};
                for (size_t q = 0; q < 7; ++q)
                    values[q].push_back(v[q]);
                c.vgprs_max = std::max(c.vgprs_max, f->vgprs);
                c.waves_min = std::min(c.waves_min, f->waves_per_simd);
            }
            c.instructions = median(values[0]);
            c.per_pixel = median(values[1]);
            c.vgprs = median(values[2]);
            c.sgprs = median(values[3]);
            c.waves_per_simd = median(values[4]);
            c.code_bytes = median(values[5]);
            c.spills = median(values[6]);
            out.rows[k].targets[run.target.name] = c;
        }
    }
}

nlohmann::ordered_json targets_json(const ModeRow& row) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    for (const auto& [t, c] : row.targets)
        j[t] = {{"instructions", c.instructions},
                {"per_pixel", c.per_pixel},
                {"vgprs", c.vgprs},
                {"vgprs_max", c.vgprs_max},
                {"sgprs", c.sgprs},
                {"waves_per_simd", c.waves_per_simd},
                {"waves_min", c.waves_min},
                {"code_bytes", c.code_bytes},
                {"spills", c.spills}};
    return j;
}

// modes.csv (a line per mode and rendered variant) and modes.json.
void add_tables(ModesBenchResult& r) {
    r.csv = "mode,variant,shaders,generate_compile_ms,spirv_bytes,spirv_bytes_per_draw,"
            "pipeline_ms,first_draw_ms,steady_ms,max_abs\n";
    nlohmann::ordered_json json = nlohmann::ordered_json::array();
    const double n = static_cast<double>(r.material_variants);
    for (const ModeRow& row : r.rows) {
        nlohmann::ordered_json variants = nlohmann::ordered_json::array();
        for (const ModeVariantTimes& v : row.variants) {
            r.csv += fmt::format("{},\"{}\",{},{:.3f},{:.0f},{:.0f},{:.3f},{:.3f},{:.4f},{:.3g}\n",
                                 row.mode, v.key, row.shaders, row.generate_compile_ms,
                                 row.spirv_bytes, row.spirv_bytes_per_draw, v.pipeline_ms,
                                 v.first_draw_ms, v.steady_ms, v.max_abs);
            variants.push_back({{"variant", v.key},
                                {"pipeline_ms", v.pipeline_ms},
                                {"first_draw_ms", v.first_draw_ms},
                                {"steady_ms", v.steady_ms},
                                {"max_abs", v.max_abs}});
        }
        json.push_back({{"mode", row.mode},
                        {"shaders", row.shaders},
                        {"generate_compile_ms", row.generate_compile_ms},
                        {"generate_compile_ms_per_variant", row.generate_compile_ms / n},
                        {"spirv_bytes", row.spirv_bytes},
                        {"spirv_bytes_per_draw", row.spirv_bytes_per_draw},
                        {"pipeline_ms", row.pipeline_ms},
                        {"first_draw_ms", row.first_draw_ms},
                        {"steady_ms", row.steady_ms},
                        {"max_abs", row.max_abs},
                        {"targets", targets_json(row)},
                        {"variants", variants}});
    }
    r.json = json.dump(2) + "\n";
    if (r.targets.empty()) return;
    // Per mode and family, the medians over the rendered variants.
    r.targets_csv = "mode,target,instructions,per_pixel,vgprs,vgprs_max,sgprs,waves_per_simd,"
                    "waves_min,code_bytes,spills\n";
    for (const ModeRow& row : r.rows)
        for (const std::string& t : r.targets) {
            const ModeTargetCost& c = row.targets.at(t);
            r.targets_csv += fmt::format(
                "{},{},{:.0f},{:.0f},{:.0f},{:.0f},{:.0f},{:.0f},{:.0f},{:.0f},{:.0f}\n", row.mode,
                t, c.instructions, c.per_pixel, c.vgprs, c.vgprs_max, c.sgprs, c.waves_per_simd,
                c.waves_min, c.code_bytes, c.spills);
        }
}

} // namespace

ModesBenchResult bench_modes(VulkanRunner& runner, const Material& m,
                             const ModesBenchOptions& options) {
    ModesBenchResult out;
    out.material = m.name;
    out.device = runner.device_info().name;
    std::vector<Variant> all;
    enumerate(m.space, [&](const Variant& v) { all.push_back(v); });
    std::sort(all.begin(), all.end(),
              [](const Variant& a, const Variant& b) { return a.key() < b.key(); });
    out.material_variants = all.size();

    Mode perm, spec, branch;
    const double perm_ms = build_mode(m, all, BuildMode::Permutations, perm, out.error);
    const double spec_ms = build_mode(m, all, BuildMode::Specialized, spec, out.error);
    const double branch_ms = build_mode(m, all, BuildMode::Branching, branch, out.error);
    if (!out.ok()) return out;
    // Every variant frozen offline (what `build --mode specialized --freeze` adds).
    std::vector<Draw> frozen_all;
    const auto t0 = Clock::now();
    for (const Variant& v : all) {
        frozen_all.push_back(draw_of(spec, v));
        if (!freeze(frozen_all.back(), out.error)) return out;
    }
    const double freeze_ms = ms_since(t0);

    auto row = [&](const std::string& name, const Mode& mode, double ms) {
        ModeRow r{name, mode.shaders.size(), ms, 0, 0, {}, 0, 0, 0, 0, {}};
        for (const auto& b : mode.builds)
            r.spirv_bytes += static_cast<double>(fragment_bytes(b));
        r.spirv_bytes_per_draw = r.spirv_bytes / static_cast<double>(mode.builds.size());
        return r;
    };
    out.rows = {row("permutations", perm, perm_ms), row("permutations A/A", perm, perm_ms),
                row("specialized", spec, spec_ms), row("specialized frozen", spec, spec_ms),
                row("branching", branch, branch_ms)};
    ModeRow& frozen_row = out.rows[3];
    frozen_row.generate_compile_ms += freeze_ms;
    frozen_row.spirv_bytes = 0;
    for (const Draw& d : frozen_all)
        frozen_row.spirv_bytes += static_cast<double>(d.frozen[0].size() * sizeof(uint32_t));
    frozen_row.spirv_bytes_per_draw = frozen_row.spirv_bytes / static_cast<double>(all.size());

    const std::vector<Variant> sample = spread(all, options.variants);
    std::vector<std::array<Draw, 5>> draws;
    for (const Variant& v : sample) {
        Draw f = frozen_all[static_cast<size_t>(
            std::find_if(all.begin(), all.end(),
                         [&](const Variant& a) { return a.key() == v.key(); }) -
            all.begin())];
        draws.push_back(
            {draw_of(perm, v), draw_of(perm, v), draw_of(spec, v), f, draw_of(branch, v)});
    }
    measure_modes(runner, sample, draws, options, out);
    if (out.ok() && !options.gpu_targets.empty()) add_mode_gpu_costs(sample, draws, options, out);
    if (out.ok()) add_tables(out);
    return out;
}

const ModeRow* ModesBenchResult::beyond(double tolerance) const {
    for (const ModeRow& row : rows)
        if (row.max_abs > tolerance) return &row;
    return nullptr;
}

} // namespace watergen
