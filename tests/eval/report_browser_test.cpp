// The comparison report in a real browser: headless Chromium (installed by scripts/setup) opens
// report.html written from a made-up comparison and takes a screenshot; the stability bench's
// page draws its log-log plots. The page must log
// nothing to the console, and the images, heat maps, plots and caustics textures must be drawn:
// each leaves colours in the screenshot that nothing else on the page has.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

#include <fmt/core.h>

#include "compare_report_support.h"
#include "watergen/eval/bench/stability_bench.h"
#include "watergen/eval/bench/stability_plot.h"
#include "watergen/eval/image/heat_map.h"
#include "watergen/eval/report/report_svg.h"

using namespace watergen;
namespace fs = std::filesystem;

namespace {

constexpr uint32_t kWindowWidth = 1400, kWindowHeight = 4600;

// Pixels of the screenshot within `tolerance` of `rgb` on every channel.
std::size_t pixels_near(const ImageRGBA8& shot, std::array<uint8_t, 3> rgb, int tolerance) {
    std::size_t n = 0;
    for (std::size_t p = 0; p < shot.pixel_count(); ++p) {
        bool near = true;
        for (int c = 0; c < 3; ++c)
            near = near && std::abs(int(shot.rgba[p * 4 + c]) - int(rgb[c])) <= tolerance;
        n += near ? 1 : 0;
    }
    return n;
}

// Runs `command` through the shell; its exit status, or -1 if it did not exit normally.
int run(const std::string& command) {
    const int status = std::system(command.c_str());
    return status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

} // namespace

TEST_CASE("the_report_renders_in_headless_chromium_without_console_messages", "[browser]") {
    INFO("headless Chromium comes from scripts/setup (Debian package chromium)");
    REQUIRE(run("command -v chromium > /dev/null") == 0);

    const fs::path dir = fs::current_path() / "scratch-report-browser";
    fs::remove_all(dir);
    fs::create_directories(dir);
    CompareReport report = test::synthetic_compare_report();
    test::add_synthetic_caustics_pass(report);
    REQUIRE_FALSE(write_compare_report(dir / "out", report));

    // --headless=new renders like the desktop browser; as root it needs --no-sandbox. `timeout`
    // turns a hang into a failure (exit 124) instead of a stuck test.
    const fs::path shot_path = dir / "shot.png", log_path = dir / "chromium.log";
    const std::string command = fmt::format(
        "timeout 60 chromium --headless=new --no-sandbox --disable-gpu --hide-scrollbars "
        "--user-data-dir='{}' --window-size={},{} --screenshot='{}' --enable-logging=stderr "
        "--v=0 'file://{}' > '{}' 2>&1",
        (dir / "profile").string(), kWindowWidth, kWindowHeight, shot_path.string(),
        (dir / "out" / kCompareReportHtml).string(), log_path.string());
    const int status = run(command);
    const std::string log = test::read_file_text(log_path);
    INFO(log);
    REQUIRE(status == 0);

    // Console messages (console.*, uncaught exceptions, blocked resources) show up as
    // "[...:INFO:CONSOLE:<line>] "<message>", source: <url> (<line>)".
    CHECK(log.find(":CONSOLE") == std::string::npos);

    std::string why;
    const auto shot = decode_png(test::read_file_text(shot_path), &why);
    INFO(why);
    REQUIRE(shot);
    CHECK(shot->width == kWindowWidth);
    CHECK(shot->height == kWindowHeight);

    // The sea of the synthetic views (linear 0.5 green: sRGB 0, 188, 0), shown 3x (192 px) in
    // the reference and the exact+sprites variant of both views: 4 x 192 x 96 pixels.
    CHECK(pixels_near(*shot, {0, 188, 0}, 3) >= 4 * 192 * 96 * 95 / 100);
    // The NaN pixel: magenta in the image, green in the CIEDE2000 map (3x3 pixels each).
    CHECK(pixels_near(*shot, {255, 0, 255}, 3) >= 9);
    CHECK(pixels_near(*shot, kHeatNonFiniteColor, 3) >= 9);
    // The blobs clip the CIEDE2000 maps at magma's top (about 80 pixels x 9 in four maps).
    CHECK(pixels_near(*shot, magma(1.0), 3) >= 2000);
    // The plots' first group colour (tab10 blue #1f77b4), points in three plots.
    CHECK(pixels_near(*shot, {31, 119, 180}, 3) >= 100);
    // The caustics pass (grey 188, shown 3x: 192 x 192) and its difference map (magma(0.5)).
    CHECK(pixels_near(*shot, {188, 188, 188}, 1) >= 192 * 192 * 95 / 100);
    CHECK(pixels_near(*shot, magma(0.5), 2) >= 192 * 192 * 95 / 100);
    // KEEP_REPORT=1 keeps the report, the screenshot and the browser log for a look.
    if (!std::getenv("KEEP_REPORT")) fs::remove_all(dir);
}

TEST_CASE("the_plot_labels_overlap_neither_each_other_nor_a_dot_in_chromium", "[browser]") {
    REQUIRE(run("command -v chromium > /dev/null") == 0);
    // A cluster as a comparison gives one: eight variants within 2% of each other in cost and
    // close in error, with labels as long as the report's, plus a few spread out.
    ScatterPlot plot{"labels", "instructions per pixel", "p99 dE00", {}};
    const char* names[] = {"fresnel=schlick specular=blinn_phong",
                           "fresnel=power specular=none",
                           "fresnel=exact specular=toman_glare",
                           "fresnel=none",
                           "fresnel=schlick",
                           "fresnel=power",
                           "specular=ggx_sun",
                           "fresnel=exact specular=none"};
    for (int i = 0; i < 8; ++i)
        plot.points.push_back({names[i], "", 1000.0 + 2.5 * i, 1.0 + 0.05 * (i % 3)});
    plot.points.push_back({"reference", "", 900, 0});
    plot.points.push_back({"waves=gerstner", "", 1400, 6});
    plot.points.push_back({"waves=sum_of_sines", "", 1300, 3});

    // The page measures what the browser drew: each label's box against every other label's and
    // every dot's (the script is the test's, not the report's).
    const fs::path dir = fs::current_path() / "scratch-plot-labels";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string page = "<!DOCTYPE html><html><body>" + scatter_svg(plot) + R"(<script>
const boxes = q => [...document.querySelectorAll(q)].map(e => e.getBoundingClientRect());
const hit = (a, b) => a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom;
const labels = boxes('text.point-label'), dots = boxes('circle');
let pairs = 0, on_dots = 0;
labels.forEach((a, i) => { labels.slice(i + 1).forEach(b => pairs += hit(a, b));
                           dots.forEach(d => on_dots += hit(a, d)); });
document.body.setAttribute('data-result', `labels=${labels.length} overlaps=${pairs} on_dots=${on_dots}`);
</script></body></html>)";
    std::ofstream(dir / "plot.html") << page;
    const std::string dom = (dir / "dom.html").string();
    REQUIRE(run(fmt::format("timeout 60 chromium --headless=new --no-sandbox --disable-gpu "
                            "--user-data-dir='{}' --dump-dom 'file://{}' > '{}' 2>/dev/null",
                            (dir / "profile").string(), (dir / "plot.html").string(), dom)) == 0);
    const std::string text = test::read_file_text(dom);
    const auto at = text.find("data-result=\"");
    REQUIRE(at != std::string::npos);
    const std::string result = text.substr(at + 13, text.find('"', at + 13) - at - 13);
    INFO(result);
    CHECK(result.find(" overlaps=0 on_dots=0") != std::string::npos);
    // The points apart from the cluster keep their labels, and the cluster's first ones find a
    // place; every dot names its point in a tooltip.
    int labels = 0;
    REQUIRE(std::sscanf(result.c_str(), "labels=%d", &labels) == 1);
    CHECK(labels >= 5);
    for (const char* apart :
         {">reference</text>", ">waves=gerstner</text>", ">waves=sum_of_sines</text>"})
        CHECK(page.find(apart) != std::string::npos);
    CHECK(test::count_occurrences(page, "<title>") == 11);
    if (!std::getenv("KEEP_REPORT")) fs::remove_all(dir);
}

TEST_CASE("the_stability_page_draws_log_log_lines_in_chromium", "[browser]") {
    REQUIRE(run("command -v chromium > /dev/null") == 0);
    // One case whose error grows tenfold per decade of time and of distance: on log-log axes its
    // points lie on a straight line, equally spaced in x and in y, inside the plot.
    std::vector<StabilityRow> rows;
    const StabilityCase c{"gerstner", "full", "screen_pass", 64};
    rows.push_back({c, {"view", "sun_glint", 0, 0, 0}, "k", {1e-5, 1e-5}});
    for (int d = 3; d <= 6; ++d) {
        const double x = std::pow(10.0, d), e = std::pow(10.0, d - 8);
        rows.push_back({c, {"time", "sun_glint", x, 0, 0}, "k", {e, e}});
        rows.push_back({c, {"distance", "sun_glint", 0, x, 0}, "k", {e, e}});
    }
    const std::string page = stability_html(rows);
    CHECK(test::count_occurrences(page, "<svg") == 2);
    CHECK(test::count_occurrences(page, "<tr>") == 1 + 9);         // the heading and every row
    CHECK(test::count_occurrences(page, "stroke-dasharray") == 2); // the origin's figure, twice

    const fs::path dir = fs::current_path() / "scratch-stability-page";
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "stability.html") << page.substr(0, page.rfind("</body>")) + R"(<script>
const out = [...document.querySelectorAll('svg')].map(svg => {
  const box = svg.getBoundingClientRect();
  const c = [...svg.querySelectorAll('circle')].map(e => e.getBoundingClientRect());
  const inside = c.every(r => r.left >= box.left && r.right <= box.right &&
                              r.top >= box.top && r.bottom <= box.bottom);
  const dx = c.slice(1).map((r, i) => r.left - c[i].left), dy = c.slice(1).map((r, i) => r.top - c[i].top);
  const even = v => v.every(d => Math.abs(d - v[0]) < 0.6);
  return `points=${c.length} inside=${inside} even_x=${even(dx)} even_y=${even(dy)} rising=${dy.every(d => d < 0)}`;
});
document.body.setAttribute('data-result', out.join(';'));
</script></body></html>)";
    const std::string dom = (dir / "dom.html").string();
    REQUIRE(run(fmt::format("timeout 60 chromium --headless=new --no-sandbox --disable-gpu "
                            "--user-data-dir='{}' --dump-dom 'file://{}' > '{}' 2>/dev/null",
                            (dir / "profile").string(), (dir / "stability.html").string(), dom)) ==
            0);
    const std::string text = test::read_file_text(dom);
    const auto at = text.find("data-result=\"");
    REQUIRE(at != std::string::npos);
    const std::string result = text.substr(at + 13, text.find('"', at + 13) - at - 13);
    const std::string one = "points=4 inside=true even_x=true even_y=true rising=true";
    CHECK(result == one + ";" + one);
    // A plot with nothing to draw says so.
    CHECK(log_log_svg("t", "x", "y", {}).find("no point to draw") != std::string::npos);
    if (!std::getenv("KEEP_REPORT")) fs::remove_all(dir);
}
