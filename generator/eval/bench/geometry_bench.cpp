#include "watergen/eval/bench/geometry_bench.h"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "watergen/eval/draw/mesh_render.h"
#include "watergen/eval/draw/variant_render.h"
#include "watergen/eval/measure/draw_cost.h"
#include "watergen/eval/scene/scene_views.h"
#include "watergen/runtime/water_grid.h"
#include "watergen/water/presets.h"

namespace watergen {

namespace {

// One timed job of a view and the row it fills.
struct Entry {
    GeometryBenchRow row;
    std::array<RenderJob, 2> jobs; // GLSL, HLSL
    const SyntheticScene* scene = nullptr;
    size_t build = 0;          // 0 screen pass, 1 mesh, 2 tessellated (the order of bench.aco)
    std::vector<double> morph; // a mesh's morph_weights per pixel
    VariantCountJob count;     // its valgrind count
};

std::string fail(const std::string& view, const std::string& what) {
    return view + ": " + what;
}

// The row's variant as `geometry`, built; an error when it does not build.
std::optional<VariantBuild> build_as(const Variant& variant, const std::string& geometry,
                                     std::string& error) {
    Variant v = variant;
    if (auto why = set_choice(v, "geometry", geometry)) {
        error = *why;
        return std::nullopt;
    }
    VariantBuild b = build_variant(v);
    if (!b.ok()) {
        error = v.key() + " did not build";
        for (const auto& d : b.diagnostics)
            if (d.severity == Severity::Error) error += ": " + d.message;
        return std::nullopt;
    }
    return b;
}

// The valgrind count of `b`'s steady draw in the view.
VariantCountJob count_job(const VariantBuild& b, uint32_t size, const std::string& view) {
    VariantCountJob job;
    job.keys = {b.shader.variant.key()};
    job.size = size;
    job.view = view;
    return job;
}

Entry mesh_entry(const VariantBuild& b, const SyntheticScene& scene, const WaterGridDesc& desc,
                 double tess_max, uint32_t size, const std::string& view) {
    Entry e;
    e.scene = &scene;
    e.build = tess_max > 0 ? 2 : 1;
    e.count = count_job(b, size, view);
    e.count.grid = desc;
    e.count.tess_max = tess_max;
    e.row.geometry = b.shader.mesh->geometry;
    e.row.grid = desc;
    e.row.tess_max = tess_max;
    const WaterGrid grid = scene_grid(scene, desc, b.shader.mesh->tessellated(), size, size);
    e.row.vertices = grid.vertex_count();
    e.row.primitives = grid_primitives(grid);
    e.morph = morph_weights(scene, desc, grid, size, size);
    std::map<std::string, std::vector<double>> values = mesh_values(scene, grid, size, size);
    if (tess_max > 0) values["tess_max"] = {tess_max};
    const MeshData mesh = grid_mesh(grid);
    for (size_t i = 0; i < 2; ++i)
        e.jobs[i] = mesh_render_job(b.languages[i], scene, mesh, values, size, size, 0);
    return e;
}

// The row's error split by the morph band (GeometryBenchRow::morph_share, morph_p99, still_p99).
void split_by_morph(const std::vector<double>& morph, const ImageRGBA32F& image,
                    const ImageRGBA32F& reference, GeometryBenchRow& row) {
    const std::vector<double> de = ciede2000_map(image, reference);
    std::vector<double> band, still;
    for (size_t p = 0; p < de.size() && p < morph.size(); ++p) {
        if (image.rgba[p * 4 + 3] == 0.0f || !std::isfinite(de[p]) || morph[p] < 0) continue;
        (morph[p] > 0 && morph[p] < 1 ? band : still).push_back(de[p]);
    }
    const double all = double(band.size() + still.size());
    row.morph_share = all > 0 ? double(band.size()) / all : 0.0;
    row.morph_p99 = band.empty() ? 0.0 : nearest_rank_percentile(band, 99);
    row.still_p99 = still.empty() ? 0.0 : nearest_rank_percentile(still, 99);
}

// A stage's instructions per invocation: the trip-count estimate, else the static count.
double per_invocation(const StageGpuCost& s) {
    return s.per_pixel ? *s.per_pixel : s.instructions;
}

// Row estimates of the frame's instructions on each AMD target (GeometryBenchRow::aco_frame).
void estimate_aco_frames(const std::vector<TargetCosts>& aco, size_t build, uint64_t pixels,
                         GeometryBenchRow& row) {
    if (build == 2) return;
    for (const TargetCosts& t : aco) {
        const PipelineGpuCost& c = t.costs.at(2 * build); // the GLSL path
        const StageGpuCost* vertex = c.stage("vertex");
        const StageGpuCost* fragment = c.stage("fragment");
        if (!c.ok() || !vertex || !fragment) continue;
        const double vertices = build == 0 ? 3.0 : double(row.vertices);
        const double covered = build == 0 ? double(pixels) : double(row.covered);
        row.aco_frame[t.run.target.name] =
            per_invocation(*vertex) * vertices + per_invocation(*fragment) * covered;
    }
}

// The entries' steady draws counted under valgrind, the screen pass (entry 0) twice.
std::string count_entries(std::vector<Entry>& entries, double& aa) {
    std::vector<VariantCountJob> jobs;
    for (const Entry& e : entries)
        jobs.push_back(e.count);
    const std::string key = jobs[0].keys[0];
    jobs[0].keys.push_back(key);
    std::string error;
    const auto counts = count_jobs(jobs, &error);
    if (!counts) return error;
    for (size_t k = 0; k < entries.size(); ++k)
        entries[k].row.instructions = (*counts)[k].at(entries[k].count.keys[0]);
    const double first = double((*counts)[0].at(key));
    aa = std::abs(double((*counts)[0].at(key + "#2")) / first - 1.0);
    return "";
}

nlohmann::ordered_json errors_json(const ImageErrorStats& s) {
    return {{"max_abs", s.max_abs},
            {"rmse", s.rmse},
            {"ciede2000_mean", s.ciede2000_mean},
            {"ciede2000_p99", s.ciede2000_p99}};
}

nlohmann::ordered_json aa_json(const std::map<std::string, RatioInterval>& aa) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    for (const auto& [view, r] : aa)
        j[view] = {{"ratio", r.ratio}, {"lo", r.lo}, {"hi", r.hi}};
    return j;
}

void write_tables(GeometryBench& bench) {
    bench.csv = "view,geometry,spacing_m,rings,levels,tess_max,vertices,primitives,covered,"
                "max_abs,rmse,ciede2000_mean,ciede2000_p99,glsl_vs_hlsl,draw_ms,draw_ratio,"
                "draw_ratio_lo,draw_ratio_hi,morph_share,morph_p99,still_p99,"
                "lavapipe_instructions";
    for (const TargetCosts& t : bench.aco)
        bench.csv += "," + t.run.target.name + "_frame_instructions";
    bench.csv += "\n";
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const GeometryBenchRow& r : bench.rows) {
        const bool mesh = r.geometry != "screen_pass";
        bench.csv += fmt::format(
            "{},{},{},{},{},{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.3g},{:.4g},{:.4g},{:.4g},"
            "{:.4g},{:.4g},{:.6g},{:.6g},{}",
            r.view, r.geometry, mesh ? r.grid.spacing : 0.0, mesh ? r.grid.ring_cells : 0u,
            mesh ? r.grid.levels : 0u, r.tess_max, r.vertices, r.primitives, r.covered,
            r.vs_exact.max_abs, r.vs_exact.rmse, r.vs_exact.ciede2000_mean,
            r.vs_exact.ciede2000_p99, r.glsl_vs_hlsl, r.draw_ms, r.draw_time.ratio, r.draw_time.lo,
            r.draw_time.hi, r.morph_share, r.morph_p99, r.still_p99, r.instructions);
        for (const TargetCosts& t : bench.aco) {
            const auto it = r.aco_frame.find(t.run.target.name);
            bench.csv += it == r.aco_frame.end() ? "," : fmt::format(",{:.6g}", it->second);
        }
        bench.csv += "\n";
        nlohmann::ordered_json j = {{"view", r.view}, {"geometry", r.geometry}};
        if (mesh)
            j["grid"] = {{"spacing", r.grid.spacing},
                         {"ring_cells", r.grid.ring_cells},
                         {"levels", r.grid.levels}};
        if (r.tess_max > 0) j["tess_max"] = r.tess_max;
        j["vertices"] = r.vertices;
        j["primitives"] = r.primitives;
        j["covered_pixels"] = r.covered;
        j["vs_exact_surface"] = errors_json(r.vs_exact);
        j["glsl_vs_hlsl_max_abs"] = r.glsl_vs_hlsl;
        if (mesh)
            j["lod_morph"] = {{"band_share", r.morph_share},
                              {"band_ciede2000_p99", r.morph_p99},
                              {"elsewhere_ciede2000_p99", r.still_p99}};
        j["draw_ms"] = r.draw_ms;
        j["draw_time_vs_screen_pass"] = {
            {"ratio", r.draw_time.ratio}, {"lo", r.draw_time.lo}, {"hi", r.draw_time.hi}};
        if (r.instructions) j["lavapipe_instructions"] = r.instructions;
        if (!r.aco_frame.empty()) j["aco_frame_instructions"] = r.aco_frame;
        rows.push_back(j);
    }
    nlohmann::ordered_json doc = {
        {"variant", bench.key},
        {"size", bench.settings.size},
        {"reference", "the screen pass with its surface search converged, in double (CPU)"},
        {"draw_time", "lavapipe (a CPU): ratio to the screen pass, interleaved rounds, 95% "
                      "bootstrap interval"},
        {"timing_trustworthy", bench.timing_trustworthy},
        {"timing_aa", aa_json(bench.timing_aa)},
        {"rows", rows}};
    if (!bench.count_aa.empty()) {
        doc["lavapipe_instructions"] = "instructions lavapipe executes for the steady draw "
                                       "(valgrind callgrind, one thread)";
        doc["instructions_aa"] = bench.count_aa;
    }
    if (!bench.aco.empty()) {
        nlohmann::ordered_json aco = nlohmann::ordered_json::object();
        for (const TargetCosts& t : bench.aco) {
            nlohmann::ordered_json pipelines = nlohmann::ordered_json::array();
            for (const PipelineGpuCost& c : t.costs) {
                nlohmann::ordered_json stages = nlohmann::ordered_json::object();
                for (const StageGpuCost& st : c.stages) {
                    nlohmann::ordered_json j = nlohmann::ordered_json::object();
                    for (const GpuCostColumn& col : gpu_cost_columns())
                        j[col.name] = st.*col.value;
                    if (st.per_pixel) j["per_invocation"] = *st.per_pixel;
                    stages[st.stage] = j;
                }
                pipelines.push_back({{"pipeline", c.name}, {"stages", stages}});
            }
            aco[t.run.target.name] = {{"device", t.run.device}, {"pipelines", pipelines}};
        }
        doc["aco"] = aco;
    }
    bench.json = doc.dump(2) + "\n";
}

} // namespace

GeometryBench run_geometry_bench(VulkanRunner& runner, const Variant& variant,
                                 const GeometryBenchSettings& settings) {
    GeometryBench bench;
    bench.settings = settings;
    for (uint32_t rings : settings.rings)
        if (auto why = water_grid_error({settings.spacing, rings, settings.levels})) {
            bench.error = "rings " + std::to_string(rings) + ": " + *why;
            return bench;
        }
    std::string error;
    const auto screen = build_as(variant, "screen_pass", error);
    const auto mesh = build_as(variant, "mesh", error);
    const auto tess = settings.tess_max.empty() ? std::optional<VariantBuild>()
                                                : build_as(variant, "tessellated", error);
    if (!error.empty()) {
        bench.error = error;
        return bench;
    }
    bench.key = mesh->shader.key();
    if (!settings.targets.empty()) {
        std::vector<const VariantBuild*> builds = {&*screen, &*mesh};
        std::vector<std::string> names = {"screen_pass", "mesh"};
        if (tess) {
            builds.push_back(&*tess);
            names.push_back("tessellated");
        }
        bench.aco = variant_gpu_costs(settings.targets, builds, names,
                                      std::filesystem::temp_directory_path());
        for (const TargetCosts& t : bench.aco) {
            if (!t.run.ok()) {
                bench.error = t.run.target.name + ": " + t.run.error;
                bench.no_device = t.run.no_device;
                return bench;
            }
            for (const PipelineGpuCost& c : t.costs)
                if (!c.ok()) {
                    bench.error = t.run.target.name + ": " + c.name + ": " + c.error;
                    return bench;
                }
        }
    }
    std::vector<std::string> views = settings.views;
    if (views.empty())
        for (const SceneView& v : scene_views())
            views.push_back(v.name);
    const uint32_t n = settings.size;
    const Graph exact =
        exact_surface_fragment(preset_material(nullptr), nullptr, mesh->shader.variant);
    for (const std::string& name : views) {
        const SyntheticScene scene = preset_scene(n, n, nullptr, name);
        const EvalResult d =
            evaluate_image(exact, "color", scene.eval_inputs(), n, n, EvalPrecision::Double);
        if (!d.ok()) {
            bench.error = fail(name, "CPU evaluator: " + d.error);
            return bench;
        }
        const ImageRGBA32F reference = to_image(d, n, n);
        std::vector<Entry> entries;
        Entry pass;
        pass.scene = &scene;
        pass.row.geometry = "screen_pass";
        pass.count = count_job(*screen, n, name);
        RenderSettings rs;
        rs.width = rs.height = n;
        for (size_t i = 0; i < 2; ++i)
            pass.jobs[i] = make_render_job(screen->languages[i], scene, rs);
        entries.push_back(pass);
        for (uint32_t rings : settings.rings)
            entries.push_back(
                mesh_entry(*mesh, scene, {settings.spacing, rings, settings.levels}, 0, n, name));
        for (double t : settings.tess_max)
            entries.push_back(
                mesh_entry(*tess, scene, {settings.patch_spacing, 16, 8}, t, n, name));
        if (settings.count) {
            const std::string why = count_entries(entries, bench.count_aa[name]);
            if (!why.empty()) {
                bench.error = fail(name, "valgrind: " + why);
                return bench;
            }
        }
        // GLSL jobs timed together (the screen pass first: the reference), HLSL drawn once.
        std::vector<RenderJob> glsl;
        for (const Entry& e : entries)
            glsl.push_back(e.jobs[0]);
        const InterleavedTiming timing =
            time_interleaved(runner, glsl, settings.rounds, settings.draws);
        if (!timing.ok()) {
            bench.error = fail(name, timing.error);
            return bench;
        }
        bench.timing_trustworthy = bench.timing_trustworthy && timing.trustworthy();
        bench.timing_aa[name] = timing.aa;
        for (size_t k = 0; k < entries.size(); ++k) {
            GeometryBenchRow& row = entries[k].row;
            row.view = name;
            RenderJob hlsl_job = entries[k].jobs[1];
            hlsl_job.timed_draws = 0;
            const RenderResult hlsl = runner.render(hlsl_job);
            if (!hlsl.ok) {
                bench.error = fail(name, row.geometry + " hlsl: " + hlsl.error);
                return bench;
            }
            const RenderResult& g = timing.results[k];
            const ImageRGBA32F image{n, n, g.rgba};
            row.vs_exact = compare_images(image, reference);
            if (!entries[k].morph.empty()) split_by_morph(entries[k].morph, image, reference, row);
            row.glsl_vs_hlsl = compare_images(image, ImageRGBA32F{n, n, hlsl.rgba}).max_abs;
            row.covered = 0;
            for (size_t p = 0; p < g.rgba.size() / 4; ++p)
                row.covered += g.rgba[p * 4 + 3] != 0.0f;
            row.draw_ms = g.steady_draw_ms;
            row.draw_time = timing.ratios[k];
            estimate_aco_frames(bench.aco, entries[k].build, uint64_t(n) * n, row);
            bench.rows.push_back(row);
        }
    }
    write_tables(bench);
    return bench;
}

uint32_t rings_within(const GeometryBench& bench, const std::string& view, double budget) {
    uint32_t best = 0;
    for (const GeometryBenchRow& r : bench.rows)
        if (r.view == view && r.geometry == "mesh" && r.vs_exact.ciede2000_p99 <= budget &&
            (best == 0 || r.grid.ring_cells < best))
            best = r.grid.ring_cells;
    return best;
}

} // namespace watergen
