#include "watergen/eval/bench/geometry_bench.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "watergen/eval/draw/mesh_render.h"
#include "watergen/eval/draw/variant_render.h"
#include "watergen/eval/scene/scene_views.h"
#include "watergen/water/presets.h"

namespace watergen {

namespace {

// One timed job of a view and the row it fills.
struct Entry {
    GeometryBenchRow row;
    std::array<RenderJob, 2> jobs; // GLSL, HLSL
    const SyntheticScene* scene = nullptr;
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

Entry mesh_entry(const VariantBuild& b, const SyntheticScene& scene, const WaterGridDesc& desc,
                 double tess_max, uint32_t size) {
    Entry e;
    e.scene = &scene;
    e.row.geometry = b.shader.mesh->geometry;
    e.row.grid = desc;
    e.row.tess_max = tess_max;
    const WaterGrid grid = scene_grid(scene, desc, b.shader.mesh->tessellated(), size, size);
    e.row.vertices = grid.vertex_count();
    e.row.primitives = grid_primitives(grid);
    std::map<std::string, std::vector<double>> values = mesh_values(scene, grid, size, size);
    if (tess_max > 0) values["tess_max"] = {tess_max};
    const MeshData mesh = grid_mesh(grid);
    for (size_t i = 0; i < 2; ++i)
        e.jobs[i] = mesh_render_job(b.languages[i], scene, mesh, values, size, size, 0);
    return e;
}

nlohmann::ordered_json errors_json(const ImageErrorStats& s) {
    return {{"max_abs", s.max_abs},
            {"rmse", s.rmse},
            {"ciede2000_mean", s.ciede2000_mean},
            {"ciede2000_p99", s.ciede2000_p99}};
}

void write_tables(GeometryBench& bench) {
    bench.csv = "view,geometry,spacing_m,rings,levels,tess_max,vertices,primitives,covered,"
                "max_abs,rmse,ciede2000_mean,ciede2000_p99,glsl_vs_hlsl,draw_ms,draw_ratio,"
                "draw_ratio_lo,draw_ratio_hi\n";
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const GeometryBenchRow& r : bench.rows) {
        const bool mesh = r.geometry != "screen_pass";
        bench.csv += fmt::format(
            "{},{},{},{},{},{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.3g},{:.4g},{:.4g},{:.4g},"
            "{:.4g}\n",
            r.view, r.geometry, mesh ? r.grid.spacing : 0.0, mesh ? r.grid.ring_cells : 0u,
            mesh ? r.grid.levels : 0u, r.tess_max, r.vertices, r.primitives, r.covered,
            r.vs_exact.max_abs, r.vs_exact.rmse, r.vs_exact.ciede2000_mean,
            r.vs_exact.ciede2000_p99, r.glsl_vs_hlsl, r.draw_ms, r.draw_time.ratio, r.draw_time.lo,
            r.draw_time.hi);
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
        j["draw_ms"] = r.draw_ms;
        j["draw_time_vs_screen_pass"] = {
            {"ratio", r.draw_time.ratio}, {"lo", r.draw_time.lo}, {"hi", r.draw_time.hi}};
        rows.push_back(j);
    }
    const nlohmann::ordered_json doc = {
        {"variant", bench.key},
        {"size", bench.settings.size},
        {"reference", "the screen pass with its surface search converged, in double (CPU)"},
        {"draw_time", "lavapipe (a CPU): ratio to the screen pass, interleaved rounds, 95% "
                      "bootstrap interval"},
        {"timing_trustworthy", bench.timing_trustworthy},
        {"rows", rows}};
    bench.json = doc.dump(2) + "\n";
}

} // namespace

GeometryBench run_geometry_bench(VulkanRunner& runner, const Variant& variant,
                                 const GeometryBenchSettings& settings) {
    GeometryBench bench;
    bench.settings = settings;
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
    std::vector<std::string> views = settings.views;
    if (views.empty())
        for (const SceneView& v : scene_views())
            views.push_back(v.name);
    const uint32_t n = settings.size;
    const WaterShader exact =
        build_water_shader(screen->shader.variant, nullptr, SurfaceSearch::Converged);
    for (const std::string& name : views) {
        const SyntheticScene scene = preset_scene(n, n, nullptr, name);
        const EvalResult d = evaluate_image(exact.fragment, "color", scene.eval_inputs(), n, n,
                                            EvalPrecision::Double);
        if (!d.ok()) {
            bench.error = fail(name, "CPU evaluator: " + d.error);
            return bench;
        }
        const ImageRGBA32F reference = to_image(d, n, n);
        std::vector<Entry> entries;
        Entry pass;
        pass.scene = &scene;
        pass.row.geometry = "screen_pass";
        RenderSettings rs;
        rs.width = rs.height = n;
        for (size_t i = 0; i < 2; ++i)
            pass.jobs[i] = make_render_job(screen->languages[i], scene, rs);
        entries.push_back(pass);
        for (uint32_t rings : settings.rings)
            entries.push_back(
                mesh_entry(*mesh, scene, {settings.spacing, rings, settings.levels}, 0, n));
        for (double t : settings.tess_max)
            entries.push_back(mesh_entry(*tess, scene, {settings.patch_spacing, 16, 8}, t, n));
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
            row.glsl_vs_hlsl = compare_images(image, ImageRGBA32F{n, n, hlsl.rgba}).max_abs;
            row.covered = 0;
            for (size_t p = 0; p < g.rgba.size() / 4; ++p)
                row.covered += g.rgba[p * 4 + 3] != 0.0f;
            row.draw_ms = g.steady_draw_ms;
            row.draw_time = timing.ratios[k];
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
