#include "watergen/eval/bench/stability_before.h"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "watergen/eval/bench/stability_bench.h"

namespace watergen {

namespace {

// The fields of one CSV line: commas separate, a field in double quotes may hold commas and
// doubled quotes. nullopt when a quote is left open.
std::optional<std::vector<std::string>> csv_fields(const std::string& line) {
    std::vector<std::string> out(1);
    bool quoted = false;
    for (size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"')
                out.back() += '"', ++i;
            else if (c == '"')
                quoted = false;
            else
                out.back() += c;
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            out.emplace_back();
        } else if (c != '\r') {
            out.back() += c;
        }
    }
    if (quoted) return std::nullopt;
    return out;
}

std::optional<double> number(const std::string& s) {
    if (s.empty()) return std::nullopt;
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (end != s.c_str() + s.size()) return std::nullopt;
    return v;
}

std::string join_key(const std::string& waves, const std::string& precision,
                     const std::string& geometry, double size, const std::string& sweep,
                     const std::string& view, double time, double offset, double elevation) {
    return fmt::format("{} {} {} {:g} {} {} {:g} {:g} {:g}", waves, precision, geometry, size,
                       sweep, view, time, offset, elevation);
}

} // namespace

std::string stability_join_key(const StabilityCase& c, const StabilityPoint& p) {
    return join_key(c.waves, c.precision, c.geometry, c.size, p.sweep, p.view, p.time, p.offset,
                    p.elevation);
}

std::optional<StabilityBeforeTable>
parse_stability_before(const std::string& text, const std::string& file, std::string& error) {
    std::istringstream in(text);
    std::string line;
    size_t line_no = 0;
    auto fail = [&](const std::string& what) {
        error = fmt::format("{}:{}: {}", file, line_no, what);
        return std::nullopt;
    };
    ++line_no;
    if (!std::getline(in, line)) return fail("empty: expected a stability.csv header");
    const auto header = csv_fields(line);
    if (!header) return fail("an unclosed quote in the header");
    std::map<std::string, size_t> column;
    for (size_t i = 0; i < header->size(); ++i)
        column[(*header)[i]] = i;
    const char* kNeeded[] = {"waves",
                             "precision",
                             "geometry",
                             "size",
                             "sweep",
                             "view",
                             "time_s",
                             "offset_m",
                             "elevation_degrees",
                             "glsl_vs_cpu_double_max_abs",
                             "glsl_de00_p99"};
    for (const char* name : kNeeded)
        if (!column.count(name))
            return fail(fmt::format("no column '{}': expected the header of a stability.csv "
                                    "(watergen bench stability)",
                                    name));
    const auto strict = column.find("strict_half_max_abs");
    StabilityBeforeTable table;
    while (std::getline(in, line)) {
        ++line_no;
        if (line.empty() || line == "\r") continue;
        const auto f = csv_fields(line);
        if (!f) return fail("an unclosed quote");
        if (f->size() != header->size())
            return fail(
                fmt::format("{} fields, expected {} (as the header)", f->size(), header->size()));
        auto at = [&](const char* name) -> const std::string& { return (*f)[column[name]]; };
        double values[6];
        const char* kNumbers[] = {
            "size",         "time_s", "offset_m", "elevation_degrees", "glsl_vs_cpu_double_max_abs",
            "glsl_de00_p99"};
        for (size_t k = 0; k < 6; ++k) {
            const auto v = number(at(kNumbers[k]));
            if (!v)
                return fail(
                    fmt::format("{} '{}': expected a number", kNumbers[k], at(kNumbers[k])));
            values[k] = *v;
        }
        StabilityBefore b{values[4], values[5], NAN};
        if (strict != column.end() && !(*f)[strict->second].empty()) {
            const auto v = number((*f)[strict->second]);
            if (!v)
                return fail(fmt::format("strict_half_max_abs '{}': expected a number or nothing",
                                        (*f)[strict->second]));
            b.strict_max_abs = *v;
        }
        const std::string key = join_key(at("waves"), at("precision"), at("geometry"), values[0],
                                         at("sweep"), at("view"), values[1], values[2], values[3]);
        if (!table.emplace(key, b).second) return fail("a second row for " + key);
    }
    return table;
}

std::optional<StabilityBeforeTable> read_stability_before(const std::string& path,
                                                          std::string& error) {
    std::ifstream file(path, std::ios::binary);
    if (!file) {
        error = path + ": cannot open for reading";
        return std::nullopt;
    }
    std::stringstream text;
    text << file.rdbuf();
    return parse_stability_before(text.str(), path, error);
}

} // namespace watergen
