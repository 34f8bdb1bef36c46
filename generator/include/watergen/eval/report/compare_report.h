// What `watergen compare` writes: ONE self-contained report.html (inline CSS, images as PNG data
// URIs, plots as inline SVG, no script, no external URL) plus compare.csv and compare.json with
// the table. The caller fills a CompareReport with renders and measurements; everything derived
// from the images (error maps, statistics, worst regions, crops, plots) is computed here.
//
// report.html, per view: the reference and every other variant side by side at the same
// exposure; their CIEDE2000 and FLIP heat maps (fixed scales, colour bars with ticks; the worst
// window outlined in cyan); each variant's worst window with some context, zoomed, beside the
// reference's and the CIEDE2000 map's;
// a table of the view's error figures. Above the views: a summary table per variant (time ratio
// with its 95% CI, cost, SPIR-V instructions, worst-over-views error figures, NaN count,
// relation) and scatter plots of cost against p99 CIEDE2000 with the Pareto front, one for all
// variants and one per axis whose choice varies (points coloured by that axis's choice).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "watergen/eval/image/error_maps.h"
#include "watergen/eval/image/image_io.h"
#include "watergen/eval/report/caustics_report.h"
#include "watergen/eval/report/figure_spool.h"

namespace watergen {

// A named camera view of the scene and the image every variant's render of it is compared to.
struct CompareView {
    std::string name;       // e.g. "overview"; shown as a heading, used in the CSV/JSON
    ImageRGBA32F reference; // linear float, e.g. the reference variant's render
    // Streamed (reference_figure()): the reference's figure made when it was rendered, the
    // image itself left empty.
    std::string reference_figure;
};

// The HTML of one variant's render of one view, made as soon as it was rendered (its image, its
// CIEDE2000 and FLIP heat maps, its worst window zoomed), so that neither the float image nor
// its per-pixel maps need be kept while the other variants and views render.
struct CompareViewFigures {
    std::string image, ciede2000, flip, crops;
    // Written to CompareReport::spool instead (the strings left empty): the same four, in order.
    std::optional<std::array<SpooledText, 4>> spooled;
};

// One variant's render of one view.
struct CompareViewResult {
    ImageRGBA32F image; // linear float, the same size as the view's reference
    // compute_error_maps(image, view.reference, report.exposure, report.pixels_per_degree);
    // left empty, the writer computes it (fill it to reuse figures already computed).
    std::optional<ErrorMaps> errors;
    // Streamed (figured_view_result()): the figures, `errors` with its per-pixel maps dropped,
    // `image` empty.
    std::optional<CompareViewFigures> figures;
    // A CPU reference only (compare_run.h's ComparedView): pixels beyond what float rounding
    // explains, and the view's largest allowance; -1: not measured.
    int64_t beyond_float_bound = -1;
    double float_bound_max = 0;
    bool float_bound_measured() const { return beyond_float_bound >= 0; }
};

struct CompareVariant {
    std::string key;                            // the variant's key, e.g. "fresnel=schlick"
    std::map<std::string, std::string> choices; // axis -> choice; plots group by these
    bool reference = false;                     // the variant the others are compared with
    // "reference", "approximates <key>", "different model", ...: shown as given.
    std::string relation;
    // Frame time of this variant / frame time of the reference, with its 95% confidence
    // interval [lo, hi]; ratio 0 = not measured (shown as "n/a", null in JSON).
    double time_ratio = 0, time_ratio_lo = 0, time_ratio_hi = 0;
    double cost = 0; // deterministic cost, instructions per pixel; 0 = not measured
    // Per AMD target (CompareReport::cost_targets): ACO's fragment instructions per pixel,
    // loops weighted by trip count (gpu_cost.h).
    std::map<std::string, double> target_costs;
    uint64_t spirv_instructions = 0;      // of the fragment shader; 0 = unknown
    std::vector<CompareViewResult> views; // one per CompareReport::views, in the same order
};

struct CompareReport {
    std::string title;
    std::string reference_key; // the key of the reference variant (shown in the header)
    std::vector<CompareView> views;
    std::vector<CompareVariant> variants; // in the order rows and images appear
    float exposure = 1.0f;                // of every image and every perceptual metric
    double pixels_per_degree = kFlipDefaultPixelsPerDegree; // FLIP's viewing condition
    std::string timing_note; // how times were measured; shown above the table
    // false: time ratios are shown greyed and marked "untrusted", with timing_note as a warning
    // (e.g. the A/A interval is wider than the effects).
    bool timing_trustworthy = true;
    std::string cost_note; // how the cost was measured (e.g. "valgrind, instructions / pixel")
    // AMD targets whose costs every variant has in target_costs ("rdna2", ...): a column, a
    // Pareto plot and front each; the variants on one target's front and dominated on another's
    // are marked (target_fronts.h).
    std::vector<std::string> cost_targets;
    // The caustics passes the variants read ("Caustics passes" section, compare.json's
    // "caustics_passes"); none: neither appears.
    std::vector<CausticsPassFigures> caustics_passes;
    std::string caustics_note; // how the passes were drawn, measured and timed
    // Where figured_view_result() puts the figures it makes (nullptr: in memory); the report is
    // then written from it one figure at a time.
    std::shared_ptr<FigureSpool> spool;
};

// Streaming a report: `report` holds the views' names and every variant's key, choices and
// reference flag (the captions read them). The reference image's figure for view `view`; and
// variant `variant`'s result of `image` against `reference`: error figures computed, figures
// made, the image and the per-pixel maps not kept.
std::string reference_figure(const CompareReport& report, const ImageRGBA32F& reference);
CompareViewResult figured_view_result(const CompareReport& report, std::size_t variant,
                                      const ImageRGBA32F& image, const ImageRGBA32F& reference);

// Names of the files written, for callers that list them.
constexpr const char* kCompareReportHtml = "report.html";
constexpr const char* kCompareCsv = "compare.csv";
constexpr const char* kCompareJson = "compare.json";

// The three files' contents by name. Fails (nullopt, reason in *error) if the report is
// inconsistent: no view, a variant without one result per view, or an image whose size differs
// from its view's reference.
std::optional<std::map<std::string, std::string>> compare_report_files(const CompareReport& report,
                                                                       std::string* error);

// Writes compare_report_files(report) plus `extra_files` (relative path -> contents) into `dir`
// as one atomic step: a staging directory beside it, then a rename over `dir` (a previous `dir`
// is replaced whole). report.html is written piece by piece (spooled figures are copied from
// the spool), never held whole in memory. Returns the error, if any; on error `dir` is as it
// was.
std::optional<std::string>
write_compare_report(const std::filesystem::path& dir, const CompareReport& report,
                     const std::map<std::string, std::string>& extra_files = {});

} // namespace watergen
