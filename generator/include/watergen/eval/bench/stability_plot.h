// The stability bench's page (stability.html): log-log plots of GPU-against-double error over
// time and over distance from the world origin, one line per case (and, dotted, its figures
// from the --before run), and the table of every row.
// Inline SVG, no script, no external resource.
#pragma once

#include <string>
#include <vector>

namespace watergen {

struct StabilityRow;

// A log-log line plot: per series its (x, y) points, drawn where both are > 0 and finite, and
// its reference (the figure at x = 0, which a log axis cannot show) as a dashed line.
struct LogLogSeries {
    std::string label;
    std::vector<std::pair<double, double>> points;
    double reference = 0; // drawn when > 0 and finite
    bool dashed = false;  // the line dotted (a run from before a change)
};
std::string log_log_svg(const std::string& title, const std::string& x_label,
                        const std::string& y_label, const std::vector<LogLogSeries>& series,
                        unsigned width = 640, unsigned height = 400);

std::string stability_html(const std::vector<StabilityRow>& rows);

} // namespace watergen
