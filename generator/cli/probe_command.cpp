// watergen probe: one node over a CSV of input tuples, on the GPU and on the CPU.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "commands.h"
#include "watergen/water/node_catalog.h"
#include "watergen/pipeline/output_writer.h"
#include "watergen/render/probe.h"

namespace watergen::cli {

namespace {

std::vector<std::string> column_names(const std::vector<ProbeField>& fields) {
    std::vector<std::string> names;
    for (const auto& f : fields) {
        const int n = component_count(f.type);
        for (int c = 0; c < n; ++c) names.push_back(n == 1 ? f.name : f.name + "." + "xyzw"[c]);
    }
    return names;
}

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) {
        const auto b = cell.find_first_not_of(" \t\r"), e = cell.find_last_not_of(" \t\r");
        cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
    }
    return cells;
}

// Reads tuples; on bad input returns false with "file:line: what was expected".
bool read_csv(const std::string& path, const std::vector<std::string>& columns, std::vector<double>& values, std::string& error) {
    std::ifstream in(path);
    if (!in) {
        error = path + ": cannot open for reading";
        return false;
    }
    const std::string expected = fmt::format("{}", fmt::join(columns, ","));
    bool header = false;
    int line_no = 0;
    for (std::string line; std::getline(in, line);) {
        ++line_no;
        if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
        const auto cells = split(line);
        if (!header) {
            if (cells != columns) {
                error = fmt::format("{}:{}: expected the header '{}'", path, line_no, expected);
                return false;
            }
            header = true;
            continue;
        }
        if (cells.size() != columns.size()) {
            error = fmt::format("{}:{}: expected {} values ({}), got {}", path, line_no, columns.size(), expected, cells.size());
            return false;
        }
        for (size_t i = 0; i < cells.size(); ++i) {
            char* end = nullptr;
            const double v = std::strtod(cells[i].c_str(), &end);
            if (cells[i].empty() || *end != '\0') {
                error = fmt::format("{}:{}: column '{}': expected a number, got '{}'", path, line_no, columns[i], cells[i]);
                return false;
            }
            values.push_back(v);
        }
    }
    if (!header) {
        error = fmt::format("{}: empty; expected the header '{}' and at least one row", path, expected);
        return false;
    }
    return true;
}

bool parse_params(const std::vector<std::string>& specs, std::map<std::string, std::vector<double>>& out, std::string& error) {
    for (const auto& spec : specs) {
        const auto eq = spec.find('=');
        if (eq == std::string::npos || eq == 0) {
            error = "--param '" + spec + "': expected name=value[,value...]";
            return false;
        }
        std::vector<double> values;
        for (const auto& cell : split(spec.substr(eq + 1))) {
            char* end = nullptr;
            values.push_back(std::strtod(cell.c_str(), &end));
            if (cell.empty() || *end != '\0') {
                error = "--param '" + spec + "': '" + cell + "' is not a number";
                return false;
            }
        }
        out[spec.substr(0, eq)] = values;
    }
    return true;
}

size_t count_non_finite(const std::vector<double>& v) {
    size_t n = 0;
    for (double x : v) n += !std::isfinite(x);
    return n;
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
    double m = 0;
    for (size_t i = 0; i < a.size(); ++i)
        if (std::isfinite(a[i]) && std::isfinite(b[i])) m = std::max(m, std::fabs(a[i] - b[i]));
    return m;
}

} // namespace

Runner add_probe_command(CLI::App& app, const Common& common) {
    struct Options {
        std::string node, in, out, language = "glsl";
        std::vector<std::string> params;
        RunnerSetup runner;
    };
    auto o = std::make_shared<Options>();
    std::vector<std::string> names;
    for (const auto& n : node_catalog()) names.push_back(n.name);
    app.add_option("--node", o->node, "node to probe: " + catalog_names())->required()->check(CLI::IsMember(names));
    app.add_option("--in", o->in, "CSV of input tuples; header = the node's input columns (vectors as name.x,name.y,...)")
        ->required();
    app.add_option("--out", o->out, "CSV to write: the inputs, then per output component gpu, cpu_double, cpu_float, cpu_half")
        ->required();
    app.add_option("--language", o->language, "language path of the compute shader: glsl or hlsl (default glsl)")
        ->check(CLI::IsMember({"glsl", "hlsl"}));
    app.add_option("--param", o->params, "override a parameter on GPU and CPU: name=value[,value...] (repeatable)");
    add_runner_options(app, o->runner);
    return [o, &common]() {
        const CatalogNode* node = find_catalog_node(o->node);
        const Graph g = probe_graph(*node);
        const ProbeLayout layout = probe_layout(g);
        std::vector<double> inputs;
        std::map<std::string, std::vector<double>> params;
        std::string error;
        if (!read_csv(o->in, column_names(layout.inputs), inputs, error) || !parse_params(o->params, params, error)) {
            std::fprintf(stderr, "watergen: error: %s\n", error.c_str());
            return kUsage;
        }
        for (const auto& [name, values] : params) {
            const Parameter* p = g.find_parameter(name);
            if (!p || values.size() != p->default_value.size()) {
                std::string known;
                for (const auto& q : g.parameters()) known += (known.empty() ? "" : ", ") + q.name;
                std::fprintf(stderr, "watergen: error: --param %s: %s (parameters of %s: %s)\n", name.c_str(),
                             p ? "wrong number of values" : "unknown parameter", o->node.c_str(), known.c_str());
                return kUsage;
            }
        }
        std::string cache;
        auto runner = create_runner(o->runner, &cache);
        if (!runner) return kNoDevice;
        const ProbeRun run = run_probe(*runner, g, o->language == "hlsl" ? Language::Hlsl : Language::Glsl, inputs, params);
        print_diagnostics(run.diagnostics, common);
        if (!run.ok()) {
            if (!run.error.empty()) std::fprintf(stderr, "watergen: error: %s\n", run.error.c_str());
            return kFailed;
        }
        std::string csv = fmt::format("{}", fmt::join(column_names(layout.inputs), ","));
        const auto outputs = column_names(layout.outputs);
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
        if (auto e = write_file_atomically(o->out, csv)) {
            std::fprintf(stderr, "watergen: error: %s\n", e->c_str());
            return kFailed;
        }
        std::printf("%s (%s path) on %s: %zu tuples, dispatch %.2f ms (pipeline %.2f ms, Mesa shader cache %s)\n",
                    o->node.c_str(), o->language.c_str(), runner->device_info().name.c_str(), run.tuples,
                    run.dispatch_ms, run.pipeline_ms, cache.c_str());
        std::printf("  non-finite results: gpu %zu, cpu double %zu, cpu float %zu, cpu half %zu\n", count_non_finite(run.gpu),
                    count_non_finite(run.cpu_double), count_non_finite(run.cpu_float), count_non_finite(run.cpu_half));
        std::printf("  max |gpu - cpu float| %.3g, max |gpu - cpu double| %.3g, max |cpu half - cpu double| %.3g\n",
                    max_abs_diff(run.gpu, run.cpu_float), max_abs_diff(run.gpu, run.cpu_double),
                    max_abs_diff(run.cpu_half, run.cpu_double));
        std::printf("  wrote %s\n", o->out.c_str());
        return kOk;
    };
}

} // namespace watergen::cli
