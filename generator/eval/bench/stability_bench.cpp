#include "watergen/eval/bench/stability_bench.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "watergen/eval/bench/stability_plot.h"
#include "watergen/eval/draw/half_render.h"
#include "watergen/eval/draw/variant_caustics.h"
#include "watergen/eval/scene/synthetic_scene.h"

namespace watergen {

namespace {

constexpr double kHour = 3600, kDay = 24 * kHour, kWeek = 7 * kDay, kYear = 365.25 * kDay;

std::string point_label(const StabilityPoint& p) {
    std::string s = fmt::format("{} t={:g}s x={:g}m", p.view, p.time, p.offset);
    if (p.elevation > 0) s += fmt::format(" elevation={:g}deg", p.elevation);
    return s;
}

double ratio(double value, double origin) {
    if (origin > 0) return value / origin;
    return value > 0 ? INFINITY : 1.0;
}

std::string optional(double v) {
    return std::isfinite(v) ? fmt::format("{:.6g}", v) : "";
}

std::string csv_row(const StabilityRow& r) {
    return fmt::format(
        "\"{}\",{},{},{},{},{},{:g},{:g},{:g},\"{}\",{:.6g},{:.6g},{:.6g},{:.6g},{},"
        "{},{},{:.6g},{:.6g},{},{},{},{},{},{},{},{},{},{}\n",
        r.key, r.what.waves, r.what.precision, r.what.geometry, r.what.size, r.where.sweep,
        r.where.time, r.where.offset, r.where.elevation, r.where.view, r.max_abs[0], r.max_abs[1],
        r.de00_p99[0], r.de00_p99[1], r.over_bound[0], r.over_bound[1], r.gpu_nan_inf,
        r.ratio_to_origin, r.ratio_de00, optional(r.strict_max_abs), optional(r.strict_de00),
        r.strict_max_ulps >= 0 ? std::to_string(r.strict_max_ulps) : "", optional(r.strict_ratio),
        optional(r.before.max_abs), optional(r.before.de00_p99), optional(r.before.strict_max_abs),
        optional(r.continuous.max_abs), optional(r.continuous.past_bound),
        r.continuous.discontinuous);
}

nlohmann::ordered_json row_json(const StabilityRow& r) {
    auto finite_or_null = [](double v) -> nlohmann::ordered_json {
        if (std::isfinite(v)) return v;
        return nullptr;
    };
    return {{"variant", r.key},
            {"waves", r.what.waves},
            {"precision", r.what.precision},
            {"geometry", r.what.geometry},
            {"size", r.what.size},
            {"sweep", r.where.sweep},
            {"view", r.where.view},
            {"time_s", r.where.time},
            {"offset_m", r.where.offset},
            {"elevation_degrees", r.where.elevation},
            {"glsl_vs_cpu_double", {{"max_abs", r.max_abs[0]}, {"de00_p99", r.de00_p99[0]}}},
            {"hlsl_vs_cpu_double", {{"max_abs", r.max_abs[1]}, {"de00_p99", r.de00_p99[1]}}},
            {"over_float_bound", {{"glsl", r.over_bound[0]}, {"hlsl", r.over_bound[1]}}},
            {"gpu_nan_inf_pixels", r.gpu_nan_inf},
            {"max_abs_over_origin", finite_or_null(r.ratio_to_origin)},
            {"de00_p99_over_origin", finite_or_null(r.ratio_de00)},
            {"strict_half_vs_cpu_half",
             {{"max_abs", finite_or_null(r.strict_max_abs)},
              {"de00_p99", finite_or_null(r.strict_de00)},
              {"max_ulps", r.strict_max_ulps >= 0 ? nlohmann::ordered_json(r.strict_max_ulps)
                                                  : nlohmann::ordered_json(nullptr)},
              {"max_abs_over_origin", finite_or_null(r.strict_ratio)}}},
            {"glsl_continuous",
             {{"max_abs", finite_or_null(r.continuous.max_abs)},
              {"past_float_bound", finite_or_null(r.continuous.past_bound)},
              {"discontinuous_pixels", r.continuous.discontinuous}}},
            {"before",
             {{"glsl_max_abs", finite_or_null(r.before.max_abs)},
              {"glsl_de00_p99", finite_or_null(r.before.de00_p99)},
              {"strict_half_max_abs", finite_or_null(r.before.strict_max_abs)}}}};
}

} // namespace

SyntheticScene stability_scene(const StabilityPoint& p, uint32_t size) {
    SceneView view = *find_scene_view(p.view);
    if (p.elevation > 0) view.pitch_degrees = -p.elevation;
    view.world_offset = {p.offset, 0.0, 0.0};
    SyntheticScene scene = make_synthetic_scene(size, size, view);
    scene.uniforms["time"] = {p.time};
    if (p.time != 0) add_caustics_inputs(scene); // the map is Gerstner at the scene's time
    return scene;
}

ContinuousError continuous_error(const VariantRender& r, size_t path) {
    ContinuousError f;
    const ImageRGBA32F& gpu = r.gpu_image[path];
    if (r.float_bound.size() * 4 != gpu.rgba.size() || r.cpu_double.rgba.size() != gpu.rgba.size())
        return {NAN, NAN, 0};
    for (size_t p = 0; p < r.float_bound.size(); ++p) {
        if (!(r.float_bound[p] <= kDiscontinuousBound)) {
            ++f.discontinuous;
            continue;
        }
        for (size_t c = 0; c < 3; ++c) {
            const double e = std::fabs(double(gpu.rgba[p * 4 + c]) - r.cpu_double.rgba[p * 4 + c]);
            f.max_abs = std::max(f.max_abs, e);
            f.past_bound = std::max(f.past_bound, e - r.float_bound[p]);
        }
    }
    return f;
}

bool stability_row_within(const StabilityRow& r, double max_ratio) {
    // The ratios are value / origin (a zero origin: infinity for any value above it); a NaN
    // fails both comparisons.
    auto within = [&](double value, double ratio_to_origin, double floor) {
        return value <= floor || ratio_to_origin <= max_ratio;
    };
    if (std::isfinite(r.continuous.past_bound) && std::isfinite(r.origin_continuous.past_bound)) {
        const double pixels = double(r.what.size) * r.what.size;
        if (!stability_within(r.continuous.past_bound, r.origin_continuous.past_bound, max_ratio,
                              kAgreementTolerance) ||
            !stability_within(double(r.continuous.discontinuous),
                              double(r.origin_continuous.discontinuous), max_ratio, pixels / 1000))
            return false;
    } else if (!within(r.max_abs[0], r.ratio_to_origin, kStabilityMaxAbsFloor)) {
        return false;
    }
    if (!within(r.de00_p99[0], r.ratio_de00, kStabilityDe00Floor)) return false;
    if (std::isfinite(r.strict_ratio) &&
        !within(r.strict_max_abs, r.strict_ratio, kStabilityMaxAbsFloor))
        return false;
    return true;
}

std::vector<double> default_stability_times() {
    return {0, kHour, kDay, kWeek, kYear};
}

std::vector<double> default_stability_offsets() {
    return {0, 1e3, 1e4, 1e5, 1e6};
}

std::vector<double> default_stability_elevations() {
    return {10, 3, 1, 0.5};
}

std::vector<StabilityPoint> stability_points(const std::vector<double>& times,
                                             const std::vector<double>& offsets,
                                             const std::vector<double>& elevations,
                                             double corner_time, double corner_offset) {
    std::vector<StabilityPoint> points;
    for (const SceneView& v : scene_views()) {
        points.push_back({"view", v.name, 0, 0, 0});
        points.push_back({"view", v.name, corner_time, corner_offset, 0});
    }
    for (double t : times)
        if (t != 0) points.push_back({"time", "sun_glint", t, 0, 0});
    for (double x : offsets)
        if (x != 0) points.push_back({"distance", "sun_glint", 0, x, 0});
    for (double e : elevations) {
        points.push_back({"elevation", "grazing", 0, 0, e});
        points.push_back({"elevation", "grazing", corner_time, corner_offset, e});
    }
    return points;
}

std::optional<Variant> stability_variant(const StabilityCase& c, std::string& error) {
    Variant v = default_variant();
    for (const auto& [axis, choice] : {std::pair<std::string, std::string>{"waves", c.waves},
                                       {"normals", "analytic"},
                                       {"precision", c.precision},
                                       {"geometry", c.geometry}})
        if (auto e = set_choice(v, axis, choice)) {
            error = *e;
            return std::nullopt;
        }
    return v;
}

StabilityBench run_stability_bench(VulkanRunner& runner, const std::vector<StabilityCase>& cases,
                                   const std::vector<StabilityPoint>& points,
                                   void (*progress)(const StabilityRow&),
                                   const StabilityBeforeTable* before) {
    StabilityBench bench;
    for (const StabilityCase& c : cases) {
        std::string error;
        const std::optional<Variant> v = stability_variant(c, error);
        if (!v) {
            bench.error = error;
            return bench;
        }
        const VariantBuild build = build_variant(*v);
        if (!build.ok()) {
            bench.error = v->key() + ": the variant did not build";
            return bench;
        }
        RenderSettings settings{c.size, c.size, 1, true};
        settings.float_bound = true;
        // The figure at the origin, per view and elevation, that the other points are held to.
        std::map<std::tuple<std::string, double>, std::array<double, 3>> origin;
        std::map<std::tuple<std::string, double>, ContinuousError> origin_continuous;
        // Strict half where the device has 16-bit arithmetic; the screen pass only (a mesh's
        // figure is against the exact surface, not a half model).
        const bool strict = c.precision == "half" && c.geometry == "screen_pass" &&
                            runner.device_info().shader_float16;
        const StrictHalfBuilds strict_builds =
            strict ? build_strict_half(*v, nullptr) : StrictHalfBuilds{};
        if (!strict_builds.ok()) {
            bench.error = strict_builds.key + ": strict half: " + strict_builds.error;
            return bench;
        }
        for (const StabilityPoint& p : points) {
            const SyntheticScene scene = stability_scene(p, c.size);
            const VariantRender r = render_variant(runner, build, scene, settings);
            if (!r.ok()) {
                bench.error = r.key + " " + point_label(p) + ": " + r.error;
                return bench;
            }
            StabilityRow row{c, p, r.key};
            const ImageErrorStats hlsl = compare_images(r.gpu_image[1], r.cpu_double);
            row.max_abs = {r.glsl_vs_cpu_double.max_abs, hlsl.max_abs};
            row.de00_p99 = {r.glsl_vs_cpu_double.ciede2000_p99, hlsl.ciede2000_p99};
            row.over_bound = {r.agreement[0].over_bound, r.agreement[1].over_bound};
            row.continuous = continuous_error(r, 0);
            row.gpu_nan_inf = r.glsl_vs_cpu_double.nan_inf_where_reference_finite +
                              hlsl.nan_inf_where_reference_finite;
            if (strict) {
                const HalfRender h = render_strict_half(runner, strict_builds, scene, settings);
                if (!h.ok()) {
                    bench.error = h.key + " " + point_label(p) + ": strict half: " + h.error;
                    return bench;
                }
                row.strict_max_abs = h.vs_cpu_half[0].max_abs;
                row.strict_de00 = h.vs_cpu_half[0].ciede2000_p99;
                row.strict_max_ulps = h.ulps_vs_cpu_half[0].max_ulps;
            }
            const auto at = std::make_tuple(p.view, p.elevation);
            if (p.time == 0 && p.offset == 0)
                origin[at] = {row.max_abs[0], row.de00_p99[0], row.strict_max_abs},
                origin_continuous[at] = row.continuous;
            if (auto it = origin.find(at); it != origin.end()) {
                row.ratio_to_origin = ratio(row.max_abs[0], it->second[0]);
                row.origin_continuous = origin_continuous[at];
                row.ratio_de00 = ratio(row.de00_p99[0], it->second[1]);
                if (strict) row.strict_ratio = ratio(row.strict_max_abs, it->second[2]);
            }
            if (before)
                if (auto it = before->find(stability_join_key(c, p)); it != before->end())
                    row.before = it->second;
            if (progress) progress(row);
            bench.rows.push_back(std::move(row));
        }
    }
    bench.csv = "variant,waves,precision,geometry,size,sweep,time_s,offset_m,elevation_degrees,"
                "view,glsl_vs_cpu_double_max_abs,hlsl_vs_cpu_double_max_abs,glsl_de00_p99,"
                "hlsl_de00_p99,glsl_over_float_bound,hlsl_over_float_bound,gpu_nan_inf_pixels,"
                "max_abs_over_origin,de00_p99_over_origin,strict_half_max_abs,strict_half_de00_p99,"
                "strict_half_max_ulps,strict_half_max_abs_over_origin,before_glsl_max_abs,"
                "before_glsl_de00_p99,before_strict_half_max_abs,glsl_continuous_max_abs,"
                "glsl_past_float_bound,discontinuous_pixels\n";
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const StabilityRow& r : bench.rows) {
        bench.csv += csv_row(r);
        rows.push_back(row_json(r));
    }
    const nlohmann::ordered_json doc = {
        {"device", runner.device_info().name},
        {"reference", "the CPU evaluator in double, same graph, same scene"},
        {"rows", rows}};
    bench.json = doc.dump(2) + "\n";
    bench.html = stability_html(bench.rows);
    return bench;
}

} // namespace watergen
