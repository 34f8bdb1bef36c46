// The scatter plots' Pareto front, axis ticks and SVG text.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "compare_report_support.h"
#include "watergen/eval/report/report_svg.h"

using namespace watergen;

TEST_CASE("the_pareto_front_keeps_exactly_the_undominated_points", "[unit][svg]") {
    const std::vector<ScatterPoint> points{
        {"a", "", 1, 5}, {"b", "", 2, 3}, {"c", "", 3, 4},   {"d", "", 4, 1},
        {"e", "", 2, 3}, {"f", "", 5, 5}, {"g", "", NAN, 0}, {"h", "", 4, 2},
    };
    // c is beaten by b (cheaper and better), f by everything, h by d (same cost, better);
    // b and e are equal, so neither dominates the other; g has no cost.
    CHECK(pareto_front(points) == std::vector<std::size_t>{0, 1, 4, 3});
    CHECK(pareto_front(std::vector<ScatterPoint>{}).empty());
}

TEST_CASE("nice_ticks_step_by_one_two_or_five_times_a_power_of_ten", "[unit][svg]") {
    AxisTicks t = nice_ticks(0, 7.3);
    CHECK(t.step == 2.0);
    CHECK(t.values == std::vector<double>{0, 2, 4, 6, 8});
    t = nice_ticks(0, 0.042);
    CHECK(t.step == Approx(0.01));
    CHECK(t.values.size() == 6);
    CHECK(t.last == Approx(0.05));
    t = nice_ticks(0, 0); // a degenerate range still draws an axis
    CHECK(t.first == 0.0);
    CHECK(t.last == 1.0);
}

TEST_CASE("scatter_svg_draws_every_finite_point_the_front_and_escaped_labels", "[unit][svg]") {
    ScatterPlot plot{"by <fresnel>", "cost", "p99 dE00", {}};
    plot.points = {{"schlick & co", "fresnel=schlick", 100, 2.0},
                   {"exact", "fresnel=exact", 120, 0.5},
                   {"slow", "fresnel=exact", 150, 1.0},
                   {"unmeasured", "fresnel=exact", NAN, 1.0}};
    const std::string svg = scatter_svg(plot);
    CHECK(svg.rfind("<svg ", 0) == 0);
    CHECK(svg.substr(svg.size() - 6) == "</svg>");
    // 3 points + 2 legend entries.
    CHECK(test::count_occurrences(svg, "<circle") == 5);
    // The two front points are ringed.
    CHECK(test::count_occurrences(svg, R"(stroke="#000" stroke-width="2.5")") == 2);
    CHECK(svg.find("schlick &amp; co") != std::string::npos);
    CHECK(svg.find("by &lt;fresnel&gt;") != std::string::npos);
    CHECK(svg.find("unmeasured") == std::string::npos);
    CHECK(svg.find("nan") == std::string::npos);
    CHECK(svg.find("Pareto front") != std::string::npos);
    CHECK(svg.find("http") == std::string::npos);

    const std::string empty = scatter_svg(ScatterPlot{"none", "x", "y", {{"a", "", NAN, NAN}}});
    CHECK(empty.find("no measured point") != std::string::npos);
}
