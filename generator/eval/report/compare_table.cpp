#include "watergen/eval/report/compare_table.h"

#include <array>
#include <cmath>

#include <fmt/core.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "watergen/eval/report/target_fronts.h"

namespace watergen {

namespace {

using Json = nlohmann::ordered_json;

constexpr std::array<ErrorColumnInfo, kErrorColumnCount> kColumns{{
    {"max_abs", "max abs", [](const ErrorMaps& m) { return m.stats.max_abs; }, false, 1.0,
     "{:.4g}"},
    {"rmse", "RMSE", [](const ErrorMaps& m) { return m.stats.rmse; }, false, 1.0, "{:.4g}"},
    {"ciede2000_mean", "mean dE00", [](const ErrorMaps& m) { return m.stats.ciede2000_mean; },
     false, 1.0, "{:.2f}"},
    {"ciede2000_p99", "p99 dE00", [](const ErrorMaps& m) { return m.stats.ciede2000_p99; }, false,
     1.0, "{:.2f}"},
    {"share_above_jnd", "% px dE00 &gt; 2.3", [](const ErrorMaps& m) { return m.share_above_jnd; },
     false, 100.0, "{:.2f}"},
    {"flip_mean", "FLIP mean", [](const ErrorMaps& m) { return m.flip.mean; }, false, 1.0,
     "{:.4f}"},
    {"flip_p99", "FLIP p99", [](const ErrorMaps& m) { return m.flip.p99; }, false, 1.0, "{:.4f}"},
    {"nan_inf_pixels", "NaN/Inf px",
     [](const ErrorMaps& m) { return double(m.stats.nan_inf_pixels); }, true, 1.0, "{:.0f}"},
}};

// The worse of two figures: NaN (nothing comparable) is worse than any number.
double worse(double a, double b) {
    if (std::isnan(a) || std::isnan(b)) return std::nan("");
    return std::max(a, b);
}

VariantSummary summarise(const std::vector<ErrorMaps>& views) {
    VariantSummary s(kErrorColumnCount, 0.0);
    for (std::size_t c = 0; c < kErrorColumnCount; ++c) {
        for (const ErrorMaps& m : views) {
            const double v = kColumns[c].value(m);
            s[c] = kColumns[c].summed ? s[c] + v : worse(s[c], v);
        }
    }
    return s;
}

std::string csv_field(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string out = "\"";
    for (char c : text)
        out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string csv_number(double v, bool measured = true) {
    if (!measured) return {};
    if (std::isnan(v)) return "nan";
    return fmt::format("{}", v);
}

std::string choices_text(const CompareVariant& v) {
    std::vector<std::string> parts;
    for (const auto& [axis, choice] : v.choices)
        parts.push_back(axis + "=" + choice);
    return fmt::format("{}", fmt::join(parts, ";"));
}

Json number_or_null(double v, bool measured = true) {
    return measured && std::isfinite(v) ? Json(v) : Json(nullptr);
}

Json view_json(const std::string& name, const ErrorMaps& m, const CompareViewResult& r) {
    Json j;
    j["view"] = name;
    for (const ErrorColumnInfo& c : kColumns)
        j[c.key] = number_or_null(c.value(m));
    j["compared_pixels"] = m.stats.compared_pixels;
    // Against a CPU reference: pixels beyond |CPU float - double| + the float error bound.
    j["pixels_beyond_float_bound"] =
        r.float_bound_measured() ? Json(r.beyond_float_bound) : Json(nullptr);
    j["float_bound_max"] = number_or_null(r.float_bound_max, r.float_bound_measured());
    j["worst_region"] = {
        {"x", m.worst.x}, {"y", m.worst.y}, {"width", m.worst.width}, {"height", m.worst.height}};
    return j;
}

} // namespace

const ErrorColumnInfo& error_column(ErrorColumn column) {
    return kColumns[static_cast<std::size_t>(column)];
}

std::optional<std::string> check_compare_report(const CompareReport& report) {
    if (report.views.empty()) return "the comparison has no view";
    if (report.variants.empty()) return "the comparison has no variant";
    for (const CompareView& view : report.views)
        if (view.reference_figure.empty() &&
            (!view.reference.well_formed() || view.reference.pixel_count() == 0))
            return fmt::format("view '{}': the reference image is empty or malformed", view.name);
    for (const CompareVariant& v : report.variants) {
        if (v.views.size() != report.views.size())
            return fmt::format("variant '{}' has {} view results for {} views", v.key,
                               v.views.size(), report.views.size());
        for (std::size_t i = 0; i < v.views.size(); ++i) {
            const ImageRGBA32F& image = v.views[i].image;
            const ImageRGBA32F& ref = report.views[i].reference;
            if (v.views[i].figures && !v.views[i].errors)
                return fmt::format("variant '{}', view '{}': figures without error figures", v.key,
                                   report.views[i].name);
            if (v.views[i].figures) {
                if (!v.views[i].errors->ok())
                    return fmt::format("variant '{}', view '{}': {}", v.key, report.views[i].name,
                                       v.views[i].errors->error);
                continue;
            }
            if (!image.well_formed() || image.width != ref.width || image.height != ref.height)
                return fmt::format("variant '{}', view '{}': image is {}x{}, the reference {}x{}",
                                   v.key, report.views[i].name, image.width, image.height,
                                   ref.width, ref.height);
            if (v.views[i].errors && !v.views[i].errors->ok())
                return fmt::format("variant '{}', view '{}': {}", v.key, report.views[i].name,
                                   v.views[i].errors->error);
        }
    }
    for (const CausticsPassFigures& p : report.caustics_passes) {
        const std::size_t texels = std::size_t{p.texels} * p.texels;
        if (texels == 0 || p.pass.size() != texels || p.reference.size() != texels)
            return fmt::format("caustics pass '{}': {} and {} texels for a {}x{} texture", p.name,
                               p.pass.size(), p.reference.size(), p.texels, p.texels);
    }
    return std::nullopt;
}

ResolvedErrors resolve_errors(const CompareReport& report) {
    ResolvedErrors r;
    for (const CompareVariant& v : report.variants) {
        std::vector<ErrorMaps>& maps = r.maps.emplace_back();
        for (std::size_t i = 0; i < v.views.size(); ++i) {
            const CompareViewResult& result = v.views[i];
            maps.push_back(result.errors
                               ? *result.errors
                               : compute_error_maps(result.image, report.views[i].reference,
                                                    report.exposure, report.pixels_per_degree));
        }
        r.summaries.push_back(summarise(maps));
    }
    return r;
}

std::string short_label(const CompareReport& report, const CompareVariant& variant) {
    if (variant.reference) return "reference";
    const CompareVariant* ref = nullptr;
    for (const CompareVariant& v : report.variants)
        if (v.reference) ref = &v;
    // Against the reference variant, or (the reference is not among them) the axes whose
    // choice varies between the variants.
    auto differs = [&](const std::string& axis, const std::string& choice) {
        if (ref) {
            const auto it = ref->choices.find(axis);
            return it == ref->choices.end() || it->second != choice;
        }
        for (const CompareVariant& v : report.variants)
            if (const auto it = v.choices.find(axis); it == v.choices.end() || it->second != choice)
                return true;
        return false;
    };
    std::vector<std::string> parts;
    for (const auto& [axis, choice] : variant.choices)
        if (differs(axis, choice)) parts.push_back(axis + "=" + choice);
    return parts.empty() ? variant.key : fmt::format("{}", fmt::join(parts, ", "));
}

std::string compare_csv(const CompareReport& report, const ResolvedErrors& errors) {
    std::string csv = "variant,view,reference,relation,choices,time_ratio,time_ratio_lo,"
                      "time_ratio_hi,timing_trustworthy,cost_per_pixel,spirv_instructions";
    for (const ErrorColumnInfo& c : kColumns)
        csv += std::string(",") + c.key;
    csv += ",pixels_beyond_float_bound,float_bound_max";
    // With AMD targets: their costs, each target's front, and whether the fronts disagree.
    const TargetFronts fronts = target_fronts(report, errors);
    const bool targeted = !report.cost_targets.empty();
    if (targeted) {
        for (const std::string& t : report.cost_targets)
            csv += fmt::format(",cost_{}", t);
        for (const std::string& t : fronts.targets)
            csv += fmt::format(",pareto_{}", t);
        csv += ",targets_disagree";
    }
    csv += "\r\n";
    for (std::size_t v = 0; v < report.variants.size(); ++v) {
        const CompareVariant& var = report.variants[v];
        const bool timed = var.time_ratio != 0;
        for (std::size_t i = 0; i < report.views.size(); ++i) {
            csv += fmt::format(
                "{},{},{},{},{},{},{},{},{},{},{}", csv_field(var.key),
                csv_field(report.views[i].name), var.reference ? "true" : "false",
                csv_field(var.relation), csv_field(choices_text(var)),
                csv_number(var.time_ratio, timed), csv_number(var.time_ratio_lo, timed),
                csv_number(var.time_ratio_hi, timed), report.timing_trustworthy ? "true" : "false",
                csv_number(var.cost, var.cost != 0),
                var.spirv_instructions ? std::to_string(var.spirv_instructions) : "");
            for (const ErrorColumnInfo& c : kColumns)
                csv += fmt::format(",{}", csv_number(c.value(errors.maps[v][i])));
            // Empty unless the reference is the CPU evaluator (the bound is its float error).
            const CompareViewResult& r = var.views[i];
            csv += fmt::format(",{},{}",
                               r.float_bound_measured() ? std::to_string(r.beyond_float_bound)
                                                        : std::string(),
                               csv_number(r.float_bound_max, r.float_bound_measured()));
            if (targeted) {
                for (const std::string& t : report.cost_targets)
                    csv += fmt::format(",{}",
                                       csv_number(target_cost(var, t), target_cost(var, t) != 0));
                for (std::size_t t = 0; t < fronts.targets.size(); ++t)
                    csv += fronts.on_front[t][v] ? ",true" : ",false";
                csv += fronts.disagree[v] ? ",true" : ",false";
            }
            csv += "\r\n";
        }
    }
    return csv;
}

std::string compare_json(const CompareReport& report, const ResolvedErrors& errors) {
    Json j;
    j["title"] = report.title;
    j["reference"] = report.reference_key;
    j["exposure"] = report.exposure;
    j["pixels_per_degree"] = report.pixels_per_degree;
    j["timing"] = {{"note", report.timing_note}, {"trustworthy", report.timing_trustworthy}};
    j["cost_note"] = report.cost_note;
    const TargetFronts fronts = target_fronts(report, errors);
    if (!report.cost_targets.empty()) j["cost_targets"] = report.cost_targets;
    j["views"] = Json::array();
    for (const CompareView& view : report.views)
        j["views"].push_back(view.name);
    j["variants"] = Json::array();
    for (std::size_t v = 0; v < report.variants.size(); ++v) {
        const CompareVariant& var = report.variants[v];
        Json jv;
        jv["key"] = var.key;
        jv["reference"] = var.reference;
        jv["relation"] = var.relation;
        jv["choices"] = var.choices;
        jv["time_ratio"] = var.time_ratio == 0 ? Json(nullptr)
                                               : Json{{"ratio", var.time_ratio},
                                                      {"lo", var.time_ratio_lo},
                                                      {"hi", var.time_ratio_hi}};
        jv["cost_per_pixel"] = number_or_null(var.cost, var.cost != 0);
        jv["spirv_instructions"] =
            var.spirv_instructions ? Json(var.spirv_instructions) : Json(nullptr);
        if (!report.cost_targets.empty()) {
            jv["target_costs"] = var.target_costs;
            Json on = Json::object();
            for (std::size_t t = 0; t < fronts.targets.size(); ++t)
                on[fronts.targets[t]] = bool(fronts.on_front[t][v]);
            jv["pareto_fronts"] = on;
            jv["targets_disagree"] = bool(fronts.disagree[v]);
        }
        Json summary;
        for (std::size_t c = 0; c < kErrorColumnCount; ++c)
            summary[kColumns[c].key] = number_or_null(errors.summaries[v][c]);
        jv["summary"] = summary;
        jv["views"] = Json::array();
        for (std::size_t i = 0; i < report.views.size(); ++i)
            jv["views"].push_back(view_json(report.views[i].name, errors.maps[v][i], var.views[i]));
        j["variants"].push_back(jv);
    }
    if (!report.caustics_passes.empty())
        j["caustics_passes"] = caustics_passes_json(report.caustics_passes, report.caustics_note);
    return j.dump(2) + "\n";
}

} // namespace watergen
