// The numbers of a comparison report (compare_report.h): error maps for every (variant, view),
// each variant's summary over its views, and the table as CSV and JSON.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "watergen/eval/report/compare_report.h"

namespace watergen {

// The error figures of the tables, in column order; one declaration for the HTML, CSV and JSON.
enum class ErrorColumn {
    MaxAbs,
    Rmse,
    Ciede2000Mean,
    Ciede2000P99,
    ShareAboveJnd,
    FlipMean,
    FlipP99,
    NanInfPixels,
    Count
};

struct ErrorColumnInfo {
    const char* key;     // CSV column and JSON member
    const char* heading; // HTML column heading
    double (*value)(const ErrorMaps&);
    bool summed;          // over views: summed (counts); otherwise the worst view (max; NaN wins)
    double display_scale; // HTML shows value * display_scale (shares as percentages)
    const char* format;   // fmt format of the HTML cell, after display_scale
};
const ErrorColumnInfo& error_column(ErrorColumn column);
constexpr std::size_t kErrorColumnCount = static_cast<std::size_t>(ErrorColumn::Count);

// A variant's figures over all its views, per ErrorColumn.
using VariantSummary = std::vector<double>;

struct ResolvedErrors {
    std::vector<std::vector<ErrorMaps>> maps; // [variant][view], given or computed
    std::vector<VariantSummary> summaries;    // [variant]
};

// What makes a report inconsistent (see compare_report_files), or nullopt.
std::optional<std::string> check_compare_report(const CompareReport& report);

// The error maps of every (variant, view): the variant's own when given, else computed. The report
// must pass check_compare_report.
ResolvedErrors resolve_errors(const CompareReport& report);

// The label of a variant in plots and captions: its choices that differ from the reference
// variant's ("fresnel=schlick, foam=none"), "reference" for the reference itself, the key when
// there is no reference variant or nothing differs.
std::string short_label(const CompareReport& report, const CompareVariant& variant);

// One row per (variant, view) with the variant's columns repeated; RFC 4180 quoting. Empty
// cells for measures that were not taken (0 in the report), "nan" for NaN figures.
std::string compare_csv(const CompareReport& report, const ResolvedErrors& errors);

// {title, reference, exposure, pixels_per_degree, timing, cost_note, views, variants: [{key,
// reference, relation, choices, time_ratio {ratio, lo, hi} | null, cost_per_pixel | null,
// spirv_instructions | null, summary {...}, views: [{view, ..., worst_region}]}]}; NaN is null.
std::string compare_json(const CompareReport& report, const ResolvedErrors& errors);

} // namespace watergen
