// A stability bench's figures from before a change (`bench stability --before FILE`): the
// stability.csv an earlier commit's bench wrote, joined to this run's rows by case and point,
// so one table shows each figure beside what it was.
#pragma once

#include <cmath>
#include <map>
#include <optional>
#include <string>

namespace watergen {

struct StabilityCase;
struct StabilityPoint;

// One row's figures before: GLSL against CPU double, and strict half against its own model
// (NaN where that run had no figure).
struct StabilityBefore {
    double max_abs = NAN, de00_p99 = NAN, strict_max_abs = NAN;
};

// By stability_join_key.
using StabilityBeforeTable = std::map<std::string, StabilityBefore>;

// The case and the point a row is joined on: waves, precision, geometry, size, sweep, view,
// time, offset and elevation (numbers as %g, as the CSV writes them).
std::string stability_join_key(const StabilityCase& c, const StabilityPoint& p);

// Reads a stability.csv (the header names its columns; those joined on and
// glsl_vs_cpu_double_max_abs and glsl_de00_p99 must be there, strict_half_max_abs may be).
// On bad input: nullopt, and `error` says "<file>:<line>: <what was expected>".
std::optional<StabilityBeforeTable>
parse_stability_before(const std::string& text, const std::string& file, std::string& error);

// The same from a file: "<path>: cannot open for reading" when it cannot be read.
std::optional<StabilityBeforeTable> read_stability_before(const std::string& path,
                                                          std::string& error);

} // namespace watergen
