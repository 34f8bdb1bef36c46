// Cost-versus-error scatter plots as inline SVG (no script, no external resource), with the
// Pareto front marked: the points no other point beats on both axes (lower is better on both).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace watergen {

struct ScatterPoint {
    std::string label; // drawn beside the point
    std::string group; // points of a group share a colour and a legend entry; "" = no legend
    double x = 0, y = 0;
};

struct ScatterPlot {
    std::string title, x_label, y_label;
    std::vector<ScatterPoint> points; // non-finite coordinates are left out of the drawing
};

// Indices of the points that no other point dominates (another point dominates p when its x and
// y are both <= p's and one is <), ordered by x, then y. Equal points are all on the front.
// Points with a non-finite coordinate are never on it.
std::vector<std::size_t> pareto_front(std::span<const ScatterPoint> points);

// Axis ticks at 1, 2 or 5 times a power of ten covering [lo, hi] with about `target` steps;
// values are multiples of step from first <= lo to last >= hi.
struct AxisTicks {
    double first = 0, last = 1, step = 1;
    std::vector<double> values;
};
AxisTicks nice_ticks(double lo, double hi, int target = 5);

// An <svg> element of the given size: both axes from 0 (or the smallest negative value) to a
// nice maximum, grid lines at the ticks, points coloured by group with a legend, Pareto-front
// points ringed in black and joined by a dashed staircase. A plot with no finite point says so.
std::string scatter_svg(const ScatterPlot& plot, uint32_t width = 600, uint32_t height = 380);

} // namespace watergen
