#include "watergen/eval/report/report_svg.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <string_view>

#include <fmt/core.h>

#include "watergen/eval/report/report_html.h"

namespace watergen {

namespace {

// matplotlib's "tab10" categorical palette: distinct hues of similar weight.
constexpr const char* kGroupColors[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                        "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

bool finite_point(const ScatterPoint& p) {
    return std::isfinite(p.x) && std::isfinite(p.y);
}

bool dominates(const ScatterPoint& a, const ScatterPoint& b) {
    return a.x <= b.x && a.y <= b.y && (a.x < b.x || a.y < b.y);
}

// Plot area in pixels and the data range it shows.
struct Frame {
    double left, top, right, bottom;
    AxisTicks xt, yt;
    double px(double x) const {
        return left + (x - xt.first) / (xt.last - xt.first) * (right - left);
    }
    double py(double y) const {
        return bottom - (y - yt.first) / (yt.last - yt.first) * (bottom - top);
    }
};

struct Box {
    double x0, y0, x1, y1;
    bool overlaps(const Box& b) const { return x0 < b.x1 && b.x0 < x1 && y0 < b.y1 && b.y0 < y1; }
};

// A point's label at font-size 11: a sans-serif character is at most ~0.6 em wide on average,
// the text 10 px above its baseline and 3 below (Chromium: 5.5 px a character, 13 px high).
constexpr double kLabelCharWidth = 6.6, kLabelAscent = 10.0, kLabelDescent = 3.0;

struct LabelSpot {
    double x, y; // baseline anchor
    const char* anchor;
};

// Where each point's label goes: the first spot around its point (right above, right below,
// left above, left below, above, below) that leaves every point's dot and every label placed
// before it clear and stays inside the plot; nullopt when none does (the dot's tooltip still
// names it). Points are labelled from the left, so the leftmost of a cluster gets the room.
std::vector<std::optional<LabelSpot>> place_labels(const std::vector<ScatterPoint>& points,
                                                   const std::vector<double>& px,
                                                   const std::vector<double>& py, const Box& area) {
    std::vector<Box> taken;
    for (std::size_t i = 0; i < points.size(); ++i)
        if (finite_point(points[i])) taken.push_back({px[i] - 6, py[i] - 6, px[i] + 6, py[i] + 6});
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < points.size(); ++i)
        if (finite_point(points[i]) && !points[i].label.empty()) order.push_back(i);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return px[a] < px[b] || (px[a] == px[b] && py[a] < py[b]);
    });
    std::vector<std::optional<LabelSpot>> out(points.size());
    for (std::size_t i : order) {
        const double w = kLabelCharWidth * double(points[i].label.size());
        const LabelSpot spots[] = {
            {px[i] + 8, py[i] - 6, "start"}, {px[i] + 8, py[i] + 14, "start"},
            {px[i] - 8, py[i] - 6, "end"},   {px[i] - 8, py[i] + 14, "end"},
            {px[i], py[i] - 10, "middle"},   {px[i], py[i] + 20, "middle"}};
        for (const LabelSpot& spot : spots) {
            const std::string_view anchor = spot.anchor;
            const double x0 = anchor == "start" ? spot.x
                              : anchor == "end" ? spot.x - w
                                                : spot.x - w / 2;
            const Box box{x0, spot.y - kLabelAscent, x0 + w, spot.y + kLabelDescent};
            if (box.x0 < area.x0 || box.x1 > area.x1 || box.y0 < area.y0 || box.y1 > area.y1)
                continue;
            if (std::any_of(taken.begin(), taken.end(),
                            [&](const Box& t) { return t.overlaps(box); }))
                continue;
            taken.push_back(box);
            out[i] = spot;
            break;
        }
    }
    return out;
}

std::string axes_svg(const Frame& f, const ScatterPlot& plot) {
    std::string s;
    for (double x : f.xt.values) {
        s += fmt::format(
            R"(<line x1="{0:.1f}" y1="{1:.1f}" x2="{0:.1f}" y2="{2:.1f}" stroke="#ddd"/>)", f.px(x),
            f.top, f.bottom);
        s += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle">{:g}</text>)", f.px(x),
                         f.bottom + 16, x);
    }
    for (double y : f.yt.values) {
        s += fmt::format(
            R"(<line x1="{1:.1f}" y1="{0:.1f}" x2="{2:.1f}" y2="{0:.1f}" stroke="#ddd"/>)", f.py(y),
            f.left, f.right);
        s += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="end">{:g}</text>)", f.left - 6,
                         f.py(y) + 4, y);
    }
    s += fmt::format(
        R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" fill="none" stroke="#444"/>)",
        f.left, f.top, f.right - f.left, f.bottom - f.top);
    s += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle">{}</text>)",
                     (f.left + f.right) / 2, f.bottom + 36, html_escape(plot.x_label));
    s += fmt::format(
        R"svg(<text transform="translate(14 {:.1f}) rotate(-90)" text-anchor="middle">{}</text>)svg",
        (f.top + f.bottom) / 2, html_escape(plot.y_label));
    s += fmt::format(R"(<text x="{:.1f}" y="16" text-anchor="middle" font-weight="bold">{}</text>)",
                     (f.left + f.right) / 2, html_escape(plot.title));
    return s;
}

// The dashed staircase through the front (sorted by x): right, then down to the next point.
std::string front_svg(const Frame& f, const ScatterPlot& plot,
                      const std::vector<std::size_t>& front) {
    if (front.empty()) return {};
    std::string path =
        fmt::format("M{:.1f} {:.1f}", f.px(plot.points[front[0]].x), f.py(plot.points[front[0]].y));
    for (std::size_t i = 1; i < front.size(); ++i) {
        const ScatterPoint& p = plot.points[front[i]];
        path += fmt::format(" H{:.1f} V{:.1f}", f.px(p.x), f.py(p.y));
    }
    return fmt::format(
        R"(<path d="{}" fill="none" stroke="#000" stroke-width="1.5" stroke-dasharray="5 3"/>)",
        path);
}

} // namespace

std::vector<std::size_t> pareto_front(std::span<const ScatterPoint> points) {
    std::vector<std::size_t> front;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!finite_point(points[i])) continue;
        const bool dominated =
            std::any_of(points.begin(), points.end(), [&](const ScatterPoint& q) {
                return finite_point(q) && dominates(q, points[i]);
            });
        if (!dominated) front.push_back(i);
    }
    std::stable_sort(front.begin(), front.end(), [&](std::size_t a, std::size_t b) {
        return points[a].x < points[b].x ||
               (points[a].x == points[b].x && points[a].y < points[b].y);
    });
    return front;
}

AxisTicks nice_ticks(double lo, double hi, int target) {
    if (!(hi > lo)) hi = lo + 1.0;
    const double raw = (hi - lo) / std::max(target, 1);
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    double step = magnitude;
    for (double m : {1.0, 2.0, 5.0, 10.0}) {
        step = m * magnitude;
        if (step >= raw) break;
    }
    AxisTicks t;
    t.step = step;
    t.first = std::floor(lo / step) * step;
    t.last = std::ceil(hi / step) * step;
    for (double v = t.first; v <= t.last + step * 0.5; v += step)
        t.values.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
    return t;
}

std::string scatter_svg(const ScatterPlot& plot, uint32_t width, uint32_t height) {
    std::map<std::string, std::size_t> groups; // name -> colour index, in order of appearance
    // Error from 0; cost over the data's span (padded), since variants often differ in cost
    // by a few percent and would sit in one column on an axis from 0.
    double x_lo = INFINITY, x_hi = -INFINITY, y_lo = 0, y_hi = 0;
    bool any = false;
    for (const ScatterPoint& p : plot.points) {
        if (!finite_point(p)) continue;
        if (!p.group.empty()) groups.emplace(p.group, groups.size());
        x_lo = std::min(x_lo, p.x), x_hi = std::max(x_hi, p.x);
        y_lo = std::min(y_lo, p.y), y_hi = std::max(y_hi, p.y);
        any = true;
    }
    if (!any) x_lo = x_hi = 0;
    const double pad = x_hi > x_lo ? 0.08 * (x_hi - x_lo) : std::max(1.0, 0.01 * std::abs(x_lo));
    x_lo -= pad, x_hi += pad;
    const double legend = 200.0;
    Frame f{64.0,
            28.0,
            width - 16.0 - legend,
            height - 48.0,
            nice_ticks(x_lo, x_hi),
            nice_ticks(y_lo, y_hi)};
    std::string s = fmt::format(
        R"(<svg width="{0}" height="{1}" viewBox="0 0 {0} {1}" font-family="sans-serif" font-size="12" class="plot">)",
        width, height);
    s += axes_svg(f, plot);
    if (!any) {
        s += fmt::format(
            R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle">no measured point</text>)",
            (f.left + f.right) / 2, (f.top + f.bottom) / 2);
        return s + "</svg>";
    }
    const std::vector<std::size_t> front = pareto_front(plot.points);
    s += front_svg(f, plot, front);
    std::vector<double> px(plot.points.size()), py(plot.points.size());
    for (std::size_t i = 0; i < plot.points.size(); ++i)
        if (finite_point(plot.points[i]))
            px[i] = f.px(plot.points[i].x), py[i] = f.py(plot.points[i].y);
    // Labels may reach into the margins, not into the legend or past the picture.
    const Box area{0.0, 0.0, f.right + 8, double(height)};
    const auto spots = place_labels(plot.points, px, py, area);
    for (std::size_t i = 0; i < plot.points.size(); ++i) {
        const ScatterPoint& p = plot.points[i];
        if (!finite_point(p)) continue;
        const bool on_front = std::find(front.begin(), front.end(), i) != front.end();
        const char* color = p.group.empty() ? kGroupColors[0] : kGroupColors[groups[p.group] % 10];
        s += fmt::format(
            R"(<circle cx="{:.1f}" cy="{:.1f}" r="5" fill="{}"{}><title>{}</title></circle>)",
            px[i], py[i], color, on_front ? R"( stroke="#000" stroke-width="2.5")" : "",
            html_escape(p.label));
        if (spots[i])
            s += fmt::format(
                R"(<text class="point-label" x="{:.1f}" y="{:.1f}" text-anchor="{}" font-size="11">{}</text>)",
                spots[i]->x, spots[i]->y, spots[i]->anchor, html_escape(p.label));
    }
    double ly = f.top + 8;
    for (const auto& [name, index] : groups) {
        s += fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="5" fill="{}"/>)", f.right + 20, ly,
                         kGroupColors[index % 10]);
        s += fmt::format(R"(<text x="{:.1f}" y="{:.1f}">{}</text>)", f.right + 30, ly + 4,
                         html_escape(name));
        ly += 18;
    }
    s += fmt::format(
        R"(<path d="M{0:.1f} {1:.1f} h20" fill="none" stroke="#000" stroke-width="1.5" stroke-dasharray="5 3"/><text x="{2:.1f}" y="{3:.1f}">Pareto front</text>)",
        f.right + 10, f.bottom - 8, f.right + 34, f.bottom - 4);
    return s + "</svg>";
}

} // namespace watergen
