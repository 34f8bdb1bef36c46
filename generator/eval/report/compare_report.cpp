#include "watergen/eval/report/compare_report.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

#include <fmt/core.h>

#include "watergen/eval/image/heat_map.h"
#include "watergen/eval/report/compare_table.h"
#include "watergen/eval/report/report_html.h"
#include "watergen/eval/report/report_svg.h"
#include "watergen/eval/report/target_fronts.h"
#include "watergen/pipeline/output/output_writer.h"

namespace watergen {

namespace {

constexpr const char* kCss = R"(
body { font-family: sans-serif; margin: 24px; color: #222; background: #fff; }
h1 { font-size: 22px; } h2 { font-size: 18px; margin-top: 32px; } h3 { font-size: 15px; }
table { border-collapse: collapse; margin: 8px 0; font-size: 13px; }
th, td { border: 1px solid #ccc; padding: 3px 8px; text-align: right; }
th { background: #f0f0f0; } td.key, th.key { text-align: left; }
tr.reference td { background: #eef6ee; }
.untrusted { color: #999; }
.warning { background: #fff3cd; border: 1px solid #e0c060; padding: 6px 10px; }
.note { color: #555; font-size: 13px; }
.row { display: flex; flex-wrap: wrap; gap: 12px; align-items: flex-start; }
figure { margin: 0; } figcaption { font-size: 12px; max-width: 260px; overflow-wrap: anywhere; }
img.pixelated { image-rendering: pixelated; }
.bar { position: relative; width: 256px; margin: 4px 0 28px 0; }
.bar .ticks span { position: absolute; top: 16px; font-size: 11px; transform: translateX(-50%); }
)";

constexpr std::array<uint8_t, 3> kOutlineColor{0, 255, 255};
constexpr uint32_t kCropDisplaySize = 192;

std::string cell_value(double v, const ErrorColumnInfo& column) {
    if (std::isnan(v)) return "n/a";
    return fmt::format(fmt::runtime(column.format), v * column.display_scale);
}

std::string time_cell(const CompareVariant& v, bool trustworthy) {
    if (v.time_ratio == 0) return "<td>n/a</td>";
    return fmt::format(R"(<td{}>{:.3f}&times; [{:.3f}, {:.3f}]{}</td>)",
                       trustworthy ? "" : R"( class="untrusted")", v.time_ratio, v.time_ratio_lo,
                       v.time_ratio_hi, trustworthy ? "" : " (untrusted)");
}

std::string error_headings() {
    std::string s;
    for (std::size_t c = 0; c < kErrorColumnCount; ++c)
        s += fmt::format("<th>{}</th>", error_column(ErrorColumn(c)).heading);
    return s;
}

std::string error_cells(const std::vector<double>& values) {
    std::string s;
    for (std::size_t c = 0; c < kErrorColumnCount; ++c)
        s += "<td>" + cell_value(values[c], error_column(ErrorColumn(c))) + "</td>";
    return s;
}

std::vector<double> view_values(const ErrorMaps& m) {
    std::vector<double> values;
    for (std::size_t c = 0; c < kErrorColumnCount; ++c)
        values.push_back(error_column(ErrorColumn(c)).value(m));
    return values;
}

// A column per AMD target, and with several targets where their fronts disagree.
std::string summary_table(const CompareReport& report, const ResolvedErrors& errors,
                          const TargetFronts& fronts) {
    std::string target_headings;
    for (const std::string& t : report.cost_targets)
        target_headings += "<th>" + html_escape(t) + " (ACO instr/px)</th>";
    const bool several = fronts.targets.size() > 1;
    std::string s = "<table><tr><th class=\"key\">variant</th><th>time ratio [95% CI]</th>"
                    "<th>cost (instr/px)</th>" +
                    target_headings + "<th>SPIR-V instr</th>" + error_headings() +
                    "<th class=\"key\">relation</th>" +
                    (several ? "<th class=\"key\">Pareto fronts</th>" : "") + "</tr>\n";
    for (std::size_t v = 0; v < report.variants.size(); ++v) {
        const CompareVariant& var = report.variants[v];
        std::string target_cells;
        for (const std::string& t : report.cost_targets) {
            const double c = target_cost(var, t);
            target_cells += "<td>" + (c != 0 ? fmt::format("{:.0f}", c) : "n/a") + "</td>";
        }
        std::string front_cell;
        if (several)
            front_cell =
                fronts.disagree[v]
                    ? "<td class=\"key warning\">" + html_escape(disagreement_text(fronts, v)) +
                          "</td>"
                    : "<td class=\"key\">" +
                          std::string(fronts.on_front[0][v] ? "on every front"
                                                            : "dominated on every target") +
                          "</td>";
        s += fmt::format(
            R"(<tr{}><td class="key" title="{}">{}</td>{}<td>{}</td>{}<td>{}</td>{}<td class="key">{}</td>{}</tr>)",
            var.reference ? R"( class="reference")" : "", html_escape(var.key),
            html_escape(short_label(report, var)), time_cell(var, report.timing_trustworthy),
            var.cost != 0 ? fmt::format("{:.1f}", var.cost) : "n/a", target_cells,
            var.spirv_instructions ? std::to_string(var.spirv_instructions) : "n/a",
            error_cells(errors.summaries[v]), html_escape(var.relation), front_cell);
        s += "\n";
    }
    return s + "</table>\n";
}

// One plot per AMD target: its cost against the error, the points grouped by whether the
// other targets agree with this front.
std::vector<std::string> target_plots(const CompareReport& report, const ResolvedErrors& errors,
                                      const TargetFronts& fronts) {
    std::vector<std::string> out;
    const std::size_t p99 = static_cast<std::size_t>(ErrorColumn::Ciede2000P99);
    for (std::size_t t = 0; t < fronts.targets.size(); ++t) {
        const std::string& name = fronts.targets[t];
        if (name == "lavapipe") continue; // the plots above
        ScatterPlot plot{"cost on " + name,
                         name + " fragment instructions per pixel (ACO)",
                         "p99 CIEDE2000 (worst view)",
                         {}};
        for (std::size_t v = 0; v < report.variants.size(); ++v) {
            const CompareVariant& var = report.variants[v];
            const double x = target_cost(var, name);
            const std::string group = !fronts.disagree[v]     ? "targets agree"
                                      : fronts.on_front[t][v] ? "on this front only, not all"
                                                              : "dominated here, on another front";
            plot.points.push_back({short_label(report, var), group, x != 0 ? x : std::nan(""),
                                   errors.summaries[v][p99]});
        }
        out.push_back(scatter_svg(plot));
    }
    return out;
}

// Cost on x when every variant has one, else SPIR-V instructions; y the worst view's p99 dE00.
std::vector<std::string> plots(const CompareReport& report, const ResolvedErrors& errors) {
    const bool all_costed = std::all_of(report.variants.begin(), report.variants.end(),
                                        [](const CompareVariant& v) { return v.cost != 0; });
    auto x_of = [&](const CompareVariant& v) {
        const double x = all_costed ? v.cost : double(v.spirv_instructions);
        return x != 0 ? x : std::nan("");
    };
    const std::string x_label = all_costed ? "cost (instructions per pixel)"
                                           : "SPIR-V instructions (cost not measured for all)";
    const std::size_t p99 = static_cast<std::size_t>(ErrorColumn::Ciede2000P99);
    auto make = [&](const std::string& title, auto group_of) {
        ScatterPlot plot{title, x_label, "p99 CIEDE2000 (worst view)", {}};
        for (std::size_t v = 0; v < report.variants.size(); ++v) {
            const CompareVariant& var = report.variants[v];
            plot.points.push_back(
                {short_label(report, var), group_of(var), x_of(var), errors.summaries[v][p99]});
        }
        return scatter_svg(plot);
    };
    std::vector<std::string> out{
        make("all variants", [](const CompareVariant& v) { return v.relation; })};
    std::map<std::string, std::set<std::string>> axis_choices;
    for (const CompareVariant& v : report.variants)
        for (const auto& [axis, choice] : v.choices)
            axis_choices[axis].insert(choice);
    for (const auto& [axis, choices] : axis_choices) {
        if (choices.size() < 2) continue;
        out.push_back(make("by " + axis, [&axis](const CompareVariant& v) {
            const auto it = v.choices.find(axis);
            return axis + "=" + (it == v.choices.end() ? "?" : it->second);
        }));
    }
    return out;
}

ImageRGBA8 srgb8(const ImageRGBA32F& image, float exposure) {
    return ImageRGBA8{image.width, image.height, tone_map_to_srgb8(image, exposure)};
}

ImageRGBA8 outlined_heat_map(const std::vector<float>& values, const ErrorMaps& m,
                             const HeatScale& scale) {
    ImageRGBA8 image = heat_map(values, m.width, m.height, scale);
    outline_region(image, m.worst, kOutlineColor);
    return image;
}

std::string heat_figure(const CompareReport& report, std::size_t v, const ErrorMaps& m, bool flip) {
    const HeatScale scale = flip ? flip_scale() : ciede2000_scale();
    return html_figure(outlined_heat_map(flip ? m.flip.values : m.ciede2000, m, scale),
                       short_label(report, report.variants[v]));
}

// Variant v's worst window with half a window of context on every side, zoomed: the reference,
// the variant and its CIEDE2000 map, the window outlined.
std::string crops_figures(const CompareReport& report, std::size_t v, const ErrorMaps& m,
                          const ImageRGBA8& reference, const ImageRGBA32F& image) {
    const PixelRegion context = grown_region(m.worst, m.worst.width / 2, m.width, m.height);
    const uint32_t zoom = std::max(1u, kCropDisplaySize / std::max(1u, context.width));
    auto zoomed = [&](const ImageRGBA8& source) {
        ImageRGBA8 z = zoom_nearest(crop(source, context), zoom);
        outline_region(z,
                       PixelRegion{(m.worst.x - context.x) * zoom, (m.worst.y - context.y) * zoom,
                                   m.worst.width * zoom, m.worst.height * zoom},
                       kOutlineColor);
        return z;
    };
    const std::string where =
        fmt::format(" around ({}, {}), {}x{}", m.worst.x, m.worst.y, m.worst.width, m.worst.height);
    return "<div class=\"row\">" + html_figure(zoomed(reference), "reference" + where) +
           html_figure(zoomed(srgb8(image, report.exposure)),
                       short_label(report, report.variants[v]) + where) +
           html_figure(zoomed(heat_map(m.ciede2000, m.width, m.height, ciede2000_scale())),
                       "CIEDE2000" + where) +
           "</div>\n";
}

// A variant's figures of one view: streamed ones as made, else made now from the image.
CompareViewFigures figures_of(const CompareReport& report, const ResolvedErrors& errors,
                              std::size_t v, std::size_t view, const ImageRGBA8* reference) {
    const CompareViewResult& result = report.variants[v].views[view];
    if (result.figures) return *result.figures;
    const ErrorMaps& m = errors.maps[v][view];
    CompareViewFigures f;
    f.image =
        html_figure(srgb8(result.image, report.exposure), short_label(report, report.variants[v]));
    f.ciede2000 = heat_figure(report, v, m, false);
    f.flip = heat_figure(report, v, m, true);
    if (reference) f.crops = crops_figures(report, v, m, *reference, result.image);
    return f;
}

std::string heat_heading(const ResolvedErrors& errors, std::size_t view, bool flip) {
    return fmt::format("<h3>{} (worst {}x{} window outlined)</h3>\n<div class=\"row\">",
                       flip ? "FLIP" : "CIEDE2000", errors.maps[0][view].worst.width,
                       errors.maps[0][view].worst.height);
}

// The four figure rows of a view, in CompareViewFigures order.
enum FigureRow { kImageRow, kCiede2000Row, kFlipRow, kCropsRow };

const std::string& row_text(const CompareViewFigures& f, int row) {
    return row == kImageRow       ? f.image
           : row == kCiede2000Row ? f.ciede2000
           : row == kFlipRow      ? f.flip
                                  : f.crops;
}

void write_view_section(std::ostream& out, const CompareReport& report,
                        const ResolvedErrors& errors, std::size_t view) {
    const CompareView& cv = report.views[view];
    out << fmt::format("<section><h2>View: {}</h2>\n<div class=\"row\">", html_escape(cv.name));
    out << (cv.reference_figure.empty() ? reference_figure(report, cv.reference)
                                        : cv.reference_figure);
    // Results given as images get their figures made here, all of the view's at once (a small
    // report); streamed ones are copied one figure at a time from where they were put.
    std::optional<ImageRGBA8> reference;
    if (!cv.reference.rgba.empty()) reference = srgb8(cv.reference, report.exposure);
    std::vector<std::optional<CompareViewFigures>> made(report.variants.size());
    for (std::size_t v = 0; v < report.variants.size(); ++v)
        if (!report.variants[v].reference && !report.variants[v].views[view].figures)
            made[v] = figures_of(report, errors, v, view, reference ? &*reference : nullptr);
    auto row = [&](int which) {
        for (std::size_t v = 0; v < report.variants.size(); ++v) {
            if (report.variants[v].reference) continue;
            const CompareViewFigures& f =
                made[v] ? *made[v] : *report.variants[v].views[view].figures;
            if (f.spooled && report.spool)
                report.spool->copy((*f.spooled)[std::size_t(which)], out);
            else
                out << row_text(f, which);
        }
    };
    row(kImageRow);
    out << "</div>\n" << heat_heading(errors, view, false);
    row(kCiede2000Row);
    out << "</div>\n"
        << html_color_bar(ciede2000_scale()) << "\n"
        << heat_heading(errors, view, true);
    row(kFlipRow);
    out << "</div>\n" << html_color_bar(flip_scale()) << "\n<h3>Worst region, zoomed</h3>\n";
    row(kCropsRow);
    // Against the CPU reference, the pixels its own float rounding does not explain.
    const bool bounded =
        std::any_of(report.variants.begin(), report.variants.end(),
                    [&](const CompareVariant& v) { return v.views[view].float_bound_measured(); });
    out << "<table><tr><th class=\"key\">variant</th>" << error_headings()
        << (bounded ? "<th>px beyond float bound</th><th>float bound max</th>" : "") << "</tr>\n";
    for (std::size_t v = 0; v < report.variants.size(); ++v) {
        const CompareViewResult& r = report.variants[v].views[view];
        std::string bound_cells;
        if (bounded)
            bound_cells = r.float_bound_measured()
                              ? fmt::format("<td>{}</td><td>{:.3g}</td>", r.beyond_float_bound,
                                            r.float_bound_max)
                              : "<td>n/a</td><td>n/a</td>";
        out << fmt::format("<tr><td class=\"key\">{}</td>{}{}</tr>\n",
                           html_escape(report.variants[v].key),
                           error_cells(view_values(errors.maps[v][view])), bound_cells);
    }
    out << "</table></section>\n";
}

void write_report_html(std::ostream& out, const CompareReport& report,
                       const ResolvedErrors& errors) {
    std::string s = fmt::format(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{0}</title>"
        "<style>{1}</style></head>\n<body><h1>{0}</h1>\n<p class=\"note\">Reference: {2}. "
        "Exposure {3:g}; FLIP at {4:g} pixels per degree; dE00 = CIEDE2000 of the tone-mapped "
        "sRGB images; error figures in the summary are the worst view's.</p>\n",
        html_escape(report.title), kCss, html_escape(report.reference_key), report.exposure,
        report.pixels_per_degree);
    if (!report.timing_note.empty())
        s += fmt::format("<p class=\"{}\">Timing: {}</p>\n",
                         report.timing_trustworthy ? "note" : "warning",
                         html_escape(report.timing_note));
    if (!report.cost_note.empty())
        s += "<p class=\"note\">Cost: " + html_escape(report.cost_note) + "</p>\n";
    const TargetFronts fronts = target_fronts(report, errors);
    s += summary_table(report, errors, fronts);
    s += "<h2>Cost against error</h2>\n<p class=\"note\">Ringed points joined by the dashed "
         "line form the Pareto front: no other variant is both cheaper and more accurate."
         "</p>\n<div class=\"row\">";
    for (const std::string& svg : plots(report, errors))
        s += svg;
    s += "</div>\n";
    if (!report.cost_targets.empty()) {
        s += "<h2>Cost on each target</h2>\n<p class=\"note\">One front per target (ACO's "
             "fragment instructions per pixel, each loop weighted by its trip count). " +
             std::string(fronts.any_disagreement()
                             ? "The targets disagree: a variant on one front is dominated on "
                               "another (the summary's last column names them)."
                             : "Every variant is on all fronts or on none: the targets agree.") +
             "</p>\n<div class=\"row\">";
        for (const std::string& svg : target_plots(report, errors, fronts))
            s += svg;
        s += "</div>\n";
    }
    s += caustics_passes_html(report.caustics_passes, report.caustics_note);
    out << s;
    for (std::size_t i = 0; i < report.views.size(); ++i)
        write_view_section(out, report, errors, i);
    out << "<p class=\"note\">Generated by watergen compare.</p>\n</body></html>\n";
}

std::string report_html(const CompareReport& report, const ResolvedErrors& errors) {
    std::ostringstream out;
    write_report_html(out, report, errors);
    return out.str();
}

} // namespace

std::string reference_figure(const CompareReport& report, const ImageRGBA32F& reference) {
    return html_figure(srgb8(reference, report.exposure), "reference: " + report.reference_key);
}

CompareViewResult figured_view_result(const CompareReport& report, std::size_t variant,
                                      const ImageRGBA32F& image, const ImageRGBA32F& reference) {
    CompareViewResult result;
    ErrorMaps m = compute_error_maps(image, reference, report.exposure, report.pixels_per_degree);
    CompareViewFigures f;
    if (m.ok() && !report.variants[variant].reference) {
        f.image = html_figure(srgb8(image, report.exposure),
                              short_label(report, report.variants[variant]));
        f.ciede2000 = heat_figure(report, variant, m, false);
        f.flip = heat_figure(report, variant, m, true);
        f.crops = crops_figures(report, variant, m, srgb8(reference, report.exposure), image);
    }
    if (report.spool) {
        f.spooled = {report.spool->append(f.image), report.spool->append(f.ciede2000),
                     report.spool->append(f.flip), report.spool->append(f.crops)};
        f.image = f.ciede2000 = f.flip = f.crops = {};
    }
    m.ciede2000 = {};
    m.flip.values = {};
    result.errors = std::move(m);
    result.figures = std::move(f);
    return result;
}

std::optional<std::map<std::string, std::string>> compare_report_files(const CompareReport& report,
                                                                       std::string* error) {
    if (auto problem = check_compare_report(report)) {
        if (error) *error = *problem;
        return std::nullopt;
    }
    const ResolvedErrors errors = resolve_errors(report);
    return std::map<std::string, std::string>{
        {kCompareReportHtml, report_html(report, errors)},
        {kCompareCsv, compare_csv(report, errors)},
        {kCompareJson, compare_json(report, errors)},
    };
}

std::optional<std::string> write_compare_report(const std::filesystem::path& dir,
                                                const CompareReport& report,
                                                const std::map<std::string, std::string>& extra) {
    if (auto problem = check_compare_report(report)) return *problem;
    const ResolvedErrors errors = resolve_errors(report);
    std::map<std::string, std::string> files{{kCompareCsv, compare_csv(report, errors)},
                                             {kCompareJson, compare_json(report, errors)}};
    for (const auto& [name, contents] : extra)
        if (name == kCompareReportHtml || !files.emplace(name, contents).second)
            return "extra file '" + name + "' has the name of a report file";
    std::string error;
    const std::filesystem::path staging = write_staged_tree(dir, files, &error);
    if (staging.empty()) return error;
    const std::filesystem::path html_path = staging / kCompareReportHtml;
    std::ofstream html(html_path, std::ios::binary);
    write_report_html(html, report, errors);
    html.close();
    if (!html || (report.spool && !report.spool->ok())) {
        const std::string why = report.spool && !report.spool->ok()
                                    ? report.spool->error()
                                    : "cannot write " + html_path.string();
        std::error_code ec;
        std::filesystem::remove_all(staging, ec);
        return why;
    }
    return commit_directory(staging, dir);
}

} // namespace watergen
