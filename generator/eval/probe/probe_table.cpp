#include "watergen/eval/probe/probe_table.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace watergen {

namespace {

std::vector<std::string> split_cells(const std::string& line) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) {
        const auto b = cell.find_first_not_of(" \t\r"), e = cell.find_last_not_of(" \t\r");
        cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
    }
    return cells;
}

// A whole cell as a number (strtod), or nullopt when it is empty or has anything after it.
std::optional<double> parse_number(const std::string& cell) {
    char* end = nullptr;
    const double v = std::strtod(cell.c_str(), &end);
    if (cell.empty() || *end != '\0') return std::nullopt;
    return v;
}

bool blank_or_comment(const std::string& line) {
    return line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#';
}

ProbeSideCount count(const std::vector<double>& v) {
    ProbeSideCount c;
    for (double x : v) {
        c.nan += std::isnan(x);
        c.inf += std::isinf(x);
    }
    return c;
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
    double m = 0;
    for (size_t i = 0; i < a.size() && i < b.size(); ++i)
        if (std::isfinite(a[i]) && std::isfinite(b[i])) m = std::max(m, std::fabs(a[i] - b[i]));
    return m;
}

} // namespace

std::vector<std::string> probe_columns(const std::vector<ProbeField>& fields) {
    std::vector<std::string> names;
    for (const auto& f : fields) {
        const int n = component_count(f.type);
        for (int c = 0; c < n; ++c)
            names.push_back(n == 1 ? f.name : f.name + "." + "xyzw"[c]);
    }
    return names;
}

std::optional<std::vector<double>> read_probe_csv(const std::string& path,
                                                  const std::vector<std::string>& columns,
                                                  std::string& error) {
    std::ifstream file(path, std::ios::binary);
    if (!file) {
        error = path + ": cannot open for reading";
        return std::nullopt;
    }
    std::stringstream text;
    text << file.rdbuf();
    return parse_probe_csv(text.str(), path, columns, error);
}

std::optional<std::vector<double>> parse_probe_csv(const std::string& text, const std::string& path,
                                                   const std::vector<std::string>& columns,
                                                   std::string& error) {
    std::istringstream in(text);
    const std::string expected = fmt::format("{}", fmt::join(columns, ","));
    std::vector<double> values;
    bool header = false;
    int line_no = 0;
    for (std::string line; std::getline(in, line);) {
        if (++line_no == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
        if (blank_or_comment(line)) continue;
        const auto cells = split_cells(line);
        if (!header) {
            if (cells != columns) {
                error = fmt::format("{}:{}: expected the header '{}'", path, line_no, expected);
                return std::nullopt;
            }
            header = true;
            continue;
        }
        if (cells.size() != columns.size()) {
            error = fmt::format("{}:{}: expected {} values ({}), got {}", path, line_no,
                                columns.size(), expected, cells.size());
            return std::nullopt;
        }
        for (size_t i = 0; i < cells.size(); ++i) {
            const auto v = parse_number(cells[i]);
            if (!v) {
                error = fmt::format("{}:{}: column '{}': expected a number, got '{}'", path,
                                    line_no, columns[i], cells[i]);
                return std::nullopt;
            }
            values.push_back(*v);
        }
    }
    if (!header) {
        error =
            fmt::format("{}: empty; expected the header '{}' and at least one row", path, expected);
        return std::nullopt;
    }
    if (values.empty()) {
        error = fmt::format("{}:{}: no rows after the header; expected at least one row of {}",
                            path, line_no, expected);
        return std::nullopt;
    }
    return values;
}

std::string probe_results_csv(const ProbeRun& run, const std::vector<double>& inputs) {
    const ProbeLayout& layout = run.layout;
    std::string csv = fmt::format("{}", fmt::join(probe_columns(layout.inputs), ","));
    const auto outputs = probe_columns(layout.outputs);
    for (const auto& name : outputs)
        csv += fmt::format(",gpu.{0},cpu_double.{0},cpu_float.{0},cpu_half.{0}", name);
    csv += "\n";
    for (size_t t = 0; t < run.tuples; ++t) {
        for (uint32_t k = 0; k < layout.input_stride; ++k)
            csv += fmt::format("{}{}", k ? "," : "", inputs[t * layout.input_stride + k]);
        for (size_t k = 0; k < outputs.size(); ++k) {
            const size_t i = t * layout.output_stride + k;
            csv += fmt::format(",{},{},{},{}", static_cast<float>(run.gpu[i]), run.cpu_double[i],
                               static_cast<float>(run.cpu_float[i]), run.cpu_half[i]);
        }
        csv += "\n";
    }
    return csv;
}

std::optional<std::string>
check_probe_parameters(const Graph& g, const std::map<std::string, std::vector<double>>& params,
                       bool allow_out_of_range) {
    for (const auto& [name, values] : params) {
        const Parameter* p = g.find_parameter(name);
        if (!p || values.size() != p->default_value.size()) {
            std::vector<std::string> known;
            for (const auto& q : g.parameters())
                known.push_back(q.name);
            return fmt::format(
                "--param {}: {} (parameters of the node: {})", name,
                p ? fmt::format("expected {} value{}, got {}", p->default_value.size(),
                                p->default_value.size() == 1 ? "" : "s", values.size())
                  : "unknown parameter",
                fmt::join(known, ", "));
        }
        if (allow_out_of_range) continue;
        for (double v : values)
            if (!std::isfinite(v) || v < p->min || v > p->max)
                return fmt::format(
                    "--param {}: {} is out of range; expected a value in [{}, {}]{}{} "
                    "(--allow-out-of-range passes it to GPU and CPU unchecked)",
                    name, v, p->min, p->max, p->unit.empty() ? "" : " ", p->unit);
    }
    return std::nullopt;
}

ProbeSummary summarize_probe(const ProbeRun& run) {
    ProbeSummary s;
    s.gpu = count(run.gpu);
    s.cpu_double = count(run.cpu_double);
    s.cpu_float = count(run.cpu_float);
    s.cpu_half = count(run.cpu_half);
    const size_t stride = run.layout.output_stride;
    const std::vector<double>& reference = run.strict_half ? run.cpu_half : run.cpu_float;
    for (size_t t = 0; t < run.tuples && stride > 0; ++t) {
        bool unstable = false;
        for (size_t k = 0; k < stride; ++k) {
            const size_t i = t * stride + k;
            unstable = unstable || (!std::isfinite(run.gpu[i]) && std::isfinite(reference[i]));
        }
        if (unstable && s.gpu_only_non_finite++ == 0) s.first_gpu_only_tuple = t;
    }
    s.max_gpu_vs_cpu_float = max_abs_diff(run.gpu, run.cpu_float);
    s.max_gpu_vs_cpu_double = max_abs_diff(run.gpu, run.cpu_double);
    s.max_half_vs_double = max_abs_diff(run.cpu_half, run.cpu_double);
    s.max_gpu_vs_cpu_half = max_abs_diff(run.gpu, run.cpu_half);
    if (run.strict_half)
        for (size_t i = 0; i < run.gpu.size(); ++i)
            s.gpu_vs_cpu_half.add(run.gpu[i], run.cpu_half[i], i);
    return s;
}

std::optional<std::map<std::string, std::vector<double>>>
parse_probe_parameters(const std::vector<std::string>& specs, std::string& error) {
    std::map<std::string, std::vector<double>> out;
    for (const auto& spec : specs) {
        const auto eq = spec.find('=');
        if (eq == std::string::npos || eq == 0) {
            error = "--param '" + spec + "': expected name=value[,value...]";
            return std::nullopt;
        }
        std::vector<double> values;
        std::stringstream cells(spec.substr(eq + 1));
        for (std::string cell; std::getline(cells, cell, ',');) {
            const auto v = parse_number(cell);
            if (!v) {
                error = "--param '" + spec + "': '" + cell + "' is not a number";
                return std::nullopt;
            }
            values.push_back(*v);
        }
        out[spec.substr(0, eq)] = values;
    }
    return out;
}

} // namespace watergen
