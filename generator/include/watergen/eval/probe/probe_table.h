// The numeric harness's tables: input tuples read from CSV, results written as CSV, and the
// summary `watergen probe` prints. Non-finite results are counted per side, never skipped
// silently: a GPU result that is NaN or Inf where the CPU float reference is finite is a
// failure of the node, reported as such.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "watergen/eval/probe/probe.h"

namespace watergen {

// "c", "view_ray.x", "view_ray.y", ...: one column per component, in layout order.
std::vector<std::string> probe_columns(const std::vector<ProbeField>& fields);

// Reads tuples of `columns` from a CSV file: a header naming the columns exactly, then one row
// per tuple ('#' comments and blank lines skipped, a UTF-8 byte order mark accepted as in
// JSON files). Errors read "file:line: what was expected"; a file without data rows is one.
std::optional<std::vector<double>> read_probe_csv(const std::string& path,
                                                  const std::vector<std::string>& columns,
                                                  std::string& error);
// The same for text already in memory, named `name` in errors.
std::optional<std::vector<double>> parse_probe_csv(const std::string& text, const std::string& name,
                                                   const std::vector<std::string>& columns,
                                                   std::string& error);

// The inputs, then per output component gpu, cpu_double, cpu_float, cpu_half.
std::string probe_results_csv(const ProbeRun& run, const std::vector<double>& inputs);

// Checks parameter overrides against the graph: known name, right size, and (unless
// `allow_out_of_range`) every value finite and within the parameter's declared range.
std::optional<std::string>
check_probe_parameters(const Graph& g, const std::map<std::string, std::vector<double>>& params,
                       bool allow_out_of_range);

// Parameter overrides from `--param name=v[,v...]` specs; values are checked against the node
// later (check_probe_parameters). Errors name the spec and what was expected.
std::optional<std::map<std::string, std::vector<double>>>
parse_probe_parameters(const std::vector<std::string>& specs, std::string& error);

struct ProbeSideCount {
    size_t nan = 0, inf = 0;
    size_t non_finite() const { return nan + inf; }
};

struct ProbeSummary {
    ProbeSideCount gpu, cpu_double, cpu_float, cpu_half;
    // Tuples with a component the GPU gives as NaN/Inf where the CPU reference is finite (CPU
    // float; CPU half for a strict-half run): the node is not stable on the GPU there.
    size_t gpu_only_non_finite = 0;
    size_t first_gpu_only_tuple = 0; // valid when gpu_only_non_finite > 0
    // Over components finite on both sides.
    double max_gpu_vs_cpu_float = 0, max_gpu_vs_cpu_double = 0, max_half_vs_double = 0;
    double max_gpu_vs_cpu_half = 0;
    HalfAgreement gpu_vs_cpu_half; // strict-half runs only; max_index is a component index
    bool gpu_stable() const { return gpu_only_non_finite == 0; }
};

ProbeSummary summarize_probe(const ProbeRun& run);

} // namespace watergen
