#include "watergen/eval/bench/stability_plot.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "watergen/eval/bench/stability_bench.h"
#include "watergen/eval/report/report_html.h"

namespace watergen {

namespace {

// Colours for up to eight series, then again.
constexpr const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                    "#ff7f0e", "#17becf", "#8c564b", "#7f7f7f"};

bool drawable(double x, double y) {
    return std::isfinite(x) && std::isfinite(y) && x > 0 && y > 0;
}

} // namespace

std::string log_log_svg(const std::string& title, const std::string& x_label,
                        const std::string& y_label, const std::vector<LogLogSeries>& series,
                        unsigned width, unsigned height) {
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (const auto& s : series) {
        for (const auto& [x, y] : s.points)
            if (drawable(x, y)) {
                x0 = std::min(x0, x), x1 = std::max(x1, x);
                y0 = std::min(y0, y), y1 = std::max(y1, y);
            }
        if (drawable(1.0, s.reference))
            y0 = std::min(y0, s.reference), y1 = std::max(y1, s.reference);
    }
    std::string svg =
        fmt::format(R"(<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" )"
                    R"(font-family="sans-serif" font-size="11">)"
                    "<text x=\"{}\" y=\"16\" text-anchor=\"middle\" "
                    "font-size=\"13\">{}</text>",
                    width, height, width / 2, html_escape(title));
    if (!(x0 <= x1)) return svg + "<text x=\"20\" y=\"40\">no point to draw</text></svg>";
    // Whole decades around the data.
    const int dx0 = int(std::floor(std::log10(x0))),
              dx1 = std::max(dx0 + 1, int(std::ceil(std::log10(x1))));
    const int dy0 = int(std::floor(std::log10(y0))),
              dy1 = std::max(dy0 + 1, int(std::ceil(std::log10(y1))));
    const double left = 64, right = width - 180.0, top = 28, bottom = height - 40.0;
    auto px = [&](double x) { return left + (std::log10(x) - dx0) / (dx1 - dx0) * (right - left); };
    auto py = [&](double y) {
        return bottom - (std::log10(y) - dy0) / (dy1 - dy0) * (bottom - top);
    };
    for (int d = dx0; d <= dx1; ++d)
        svg += fmt::format(
            "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#ddd\"/>"
            "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">1e{4}</text>",
            px(std::pow(10.0, d)), top, bottom, bottom + 14, d);
    for (int d = dy0; d <= dy1; ++d)
        svg += fmt::format(
            "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>"
            "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">1e{5}</text>",
            left, py(std::pow(10.0, d)), right, left - 4, py(std::pow(10.0, d)) + 4, d);
    svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
                       (left + right) / 2, height - 8, html_escape(x_label));
    svg += fmt::format(
        "<text transform=\"translate(14,{}) rotate(-90)\" text-anchor=\"middle\">{}</text>",
        (top + bottom) / 2, html_escape(y_label));
    for (size_t i = 0; i < series.size(); ++i) {
        const char* colour = kColours[i % std::size(kColours)];
        std::string line;
        for (const auto& [x, y] : series[i].points)
            if (drawable(x, y)) {
                line += fmt::format("{:.1f},{:.1f} ", px(x), py(y));
                svg += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"2.5\" fill=\"{}\"/>",
                                   px(x), py(y), colour);
            }
        svg += fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"{}\"{}/>", line, colour,
                           series[i].dashed ? " stroke-dasharray=\"1 3\"" : "");
        if (drawable(1.0, series[i].reference))
            svg +=
                fmt::format("<line x1=\"{}\" y1=\"{:.1f}\" x2=\"{}\" y2=\"{:.1f}\" stroke=\"{}\" "
                            "stroke-dasharray=\"4 3\"/>",
                            left, py(series[i].reference), right, py(series[i].reference), colour);
        svg += fmt::format("<text x=\"{}\" y=\"{}\" fill=\"{}\">{}</text>", right + 8,
                           top + 12 + 14 * double(i), colour, html_escape(series[i].label));
    }
    return svg + "</svg>";
}

std::string stability_html(const std::vector<StabilityRow>& rows) {
    // One series per case: the time sweep and the distance sweep, both in sun_glint, with the
    // case's figure at the origin (t = 0, offset 0: no place on a log axis) dashed.
    std::map<std::string, LogLogSeries> by_time, by_distance;
    for (const StabilityRow& r : rows) {
        const std::string label = fmt::format("{} {} {} {}", r.what.waves, r.what.precision,
                                              r.what.geometry, r.what.size);
        if (std::isfinite(r.before.max_abs)) {
            const std::string was = label + " before";
            if (r.where.sweep == "time") {
                by_time[was].dashed = true;
                by_time[was].points.push_back({r.where.time, r.before.max_abs});
            }
            if (r.where.sweep == "distance") {
                by_distance[was].dashed = true;
                by_distance[was].points.push_back({r.where.offset, r.before.max_abs});
            }
        }
        if (r.where.view == "sun_glint" && r.where.time == 0 && r.where.offset == 0)
            by_time[label].reference = by_distance[label].reference = r.max_abs[0];
        if (r.where.sweep == "time") by_time[label].points.push_back({r.where.time, r.max_abs[0]});
        if (r.where.sweep == "distance")
            by_distance[label].points.push_back({r.where.offset, r.max_abs[0]});
    }
    auto values = [](std::map<std::string, LogLogSeries>& m) {
        std::vector<LogLogSeries> v;
        for (auto& [label, s] : m) {
            s.label = label;
            v.push_back(s);
        }
        return v;
    };
    std::string html =
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\">"
        "<title>watergen bench stability</title><style>body{font-family:sans-serif}"
        "td,th{padding:2px 6px;text-align:right}td.k{text-align:left}</style>"
        "</head><body><h1>Stability: GPU against the CPU in double</h1>\n<p>"
        "The same graph in double over the same scene moved by its world offset; "
        "GLSL path, max abs over linear RGB; dashed: the figure at the origin at time 0; dotted: "
        "the --before run's figures, where given.</p>\n";
    html += log_log_svg("sun_glint, world origin: error against time", "time (s)",
                        "max abs vs double", values(by_time)) +
            "\n";
    html += log_log_svg("sun_glint, time 0: error against distance from the origin", "distance (m)",
                        "max abs vs double", values(by_distance)) +
            "\n";
    html += "<table><tr><th>variant</th><th>sweep</th><th>view</th><th>time (s)</th>"
            "<th>offset (m)</th><th>elevation</th><th>GLSL max abs</th><th>HLSL max abs</th>"
            "<th>GLSL dE00 p99</th><th>over bound</th><th>x origin</th><th>GLSL max abs "
            "before</th></tr>\n";
    for (const StabilityRow& r : rows)
        html += fmt::format(
            "<tr><td class=\"k\">{}</td><td class=\"k\">{}</td><td class=\"k\">{}"
            "</td><td>{:g}</td><td>{:g}</td><td>{:g}</td><td>{:.3g}</td><td>{:.3g}"
            "</td><td>{:.3g}</td><td>{}</td><td>{:.3g}</td><td>{}</td></tr>\n",
            html_escape(r.key), r.where.sweep, r.where.view, r.where.time, r.where.offset,
            r.where.elevation, r.max_abs[0], r.max_abs[1], r.de00_p99[0],
            r.over_bound[0] + r.over_bound[1], r.ratio_to_origin,
            std::isfinite(r.before.max_abs) ? fmt::format("{:.3g}", r.before.max_abs) : "");
    return html + "</table></body></html>\n";
}

} // namespace watergen
