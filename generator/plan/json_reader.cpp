#include "watergen/plan/json_reader.h"

#include <algorithm>
#include <set>

#include "watergen/ir/core/text.h"

namespace watergen {

std::optional<JsonSource> load_json(const std::filesystem::path& path, Diagnostics& diagnostics) {
    Diagnostic error;
    auto src = JsonSource::load(path, &error);
    if (!src) diagnostics.push_back(error);
    return src;
}

bool JsonReader::fail(const std::string& pointer, const std::string& what) {
    diagnostics_.push_back(source_.error(pointer, what));
    return false;
}

bool JsonReader::has(const std::string& pointer) const {
    return source_.find(pointer) != nullptr;
}

const Json& JsonReader::at(const std::string& pointer) const {
    if (const Json* value = source_.find(pointer)) return *value;
    return source_.root().at(Json::json_pointer(pointer)); // throws, naming the pointer
}

std::vector<std::string> JsonReader::members(const std::string& pointer) const {
    std::vector<std::string> names;
    for (const auto& [k, _] : at(pointer).items())
        names.push_back(k);
    return names;
}

bool JsonReader::keys(const std::string& pointer, const std::vector<std::string>& allowed,
                      const std::vector<std::string>& required, const std::string& missing_note) {
    const Json& v = at(pointer);
    if (!v.is_object())
        return fail(pointer,
                    "expected an object with keys " + join(allowed) + ", got " + json_describe(v));
    for (const auto& [k, _] : v.items())
        if (std::find(allowed.begin(), allowed.end(), k) == allowed.end())
            return fail(json_child(pointer, k),
                        "unknown key '" + k + "'; expected one of " + join(allowed));
    for (const auto& k : required)
        if (!v.contains(k))
            return fail(pointer, "missing key '" + k + "'" +
                                     (missing_note.empty() ? "" : " " + missing_note));
    return true;
}

bool JsonReader::object(const std::string& pointer, const std::string& expected) {
    const Json& v = at(pointer);
    return v.is_object() || fail(pointer, "expected " + expected + ", got " + json_describe(v));
}

bool JsonReader::array(const std::string& pointer, const std::string& expected) {
    const Json& v = at(pointer);
    return v.is_array() || fail(pointer, "expected " + expected + ", got " + json_describe(v));
}

bool JsonReader::string(const std::string& pointer, std::string& out) {
    const Json& v = at(pointer);
    if (!v.is_string()) return fail(pointer, "expected a string, got " + json_describe(v));
    out = v.get<std::string>();
    return read(pointer);
}

bool JsonReader::boolean(const std::string& pointer, bool& out) {
    const Json& v = at(pointer);
    if (!v.is_boolean()) return fail(pointer, "expected true or false, got " + json_describe(v));
    out = v.get<bool>();
    return read(pointer);
}

bool JsonReader::number(const std::string& pointer, double& out) {
    const Json& v = at(pointer);
    if (!v.is_number()) return fail(pointer, "expected a number, got " + json_describe(v));
    out = v.get<double>();
    return read(pointer);
}

bool JsonReader::string_in(const std::string& pointer, const std::vector<std::string>& allowed,
                           std::string& out) {
    if (!string(pointer, out)) return false;
    if (std::find(allowed.begin(), allowed.end(), out) == allowed.end())
        return fail(pointer, "unknown value '" + out + "'; expected one of " + join(allowed));
    return true;
}

bool JsonReader::strings(const std::string& pointer, std::vector<std::string>& out) {
    const Json& v = at(pointer);
    if (!v.is_array())
        return fail(pointer, "expected an array of strings, got " + json_describe(v));
    out.assign(v.size(), "");
    for (size_t i = 0; i < v.size(); ++i)
        if (!string(json_child(pointer, i), out[i])) return false;
    return read(pointer);
}

bool JsonReader::strings_in(const std::string& pointer, const std::vector<std::string>& allowed,
                            std::vector<std::string>& out) {
    const Json& v = at(pointer);
    if (!v.is_array())
        return fail(pointer, "expected an array of strings (" + join(allowed) + "), got " +
                                 json_describe(v));
    out.assign(v.size(), "");
    std::set<std::string> seen;
    for (size_t i = 0; i < v.size(); ++i) {
        if (!string_in(json_child(pointer, i), allowed, out[i])) return false;
        if (!seen.insert(out[i]).second)
            return fail(json_child(pointer, i), "'" + out[i] + "' is listed twice");
    }
    return read(pointer);
}

bool JsonReader::numbers(const std::string& pointer, std::vector<double>& out, size_t min_count) {
    const Json& v = at(pointer);
    if (v.is_number()) {
        out = {v.get<double>()};
        return read(pointer);
    }
    if (!v.is_array() || v.size() < min_count)
        return fail(pointer, "expected a number or an array of numbers, got " + json_describe(v));
    out.assign(v.size(), 0.0);
    for (size_t i = 0; i < v.size(); ++i)
        if (!number(json_child(pointer, i), out[i])) return false;
    return read(pointer);
}

bool JsonReader::range(const std::string& pointer, double& min, double& max,
                       const NumberBounds* bounds) {
    const Json& v = at(pointer);
    if (!v.is_object())
        return fail(pointer, "expected an object {\"min\": number, \"max\": number}, got " +
                                 json_describe(v));
    for (const auto& [k, _] : v.items())
        if (k != "min" && k != "max")
            return fail(json_child(pointer, k), "unknown key '" + k + "'; expected min or max");
    for (const char* k : {"min", "max"})
        if (!v.contains(k)) return fail(pointer, std::string("missing key '") + k + "'");
    if (!number(pointer + "/min", min) || !number(pointer + "/max", max)) return false;
    read(pointer);
    if (bounds) {
        const std::string unit = bounds->unit.empty() ? "" : " " + bounds->unit;
        for (const auto& [k, x] : {std::pair{"/min", min}, std::pair{"/max", max}})
            if (x < bounds->min || x > bounds->max)
                return fail(pointer + k, spell_number(x) + unit +
                                             " is out of range; expected a value in [" +
                                             spell_number(bounds->min) + ", " +
                                             spell_number(bounds->max) + "]" + unit);
    }
    if (min > max)
        return fail(pointer, "min " + spell_number(min) + " is above max " + spell_number(max) +
                                 "; expected min <= max");
    return true;
}

} // namespace watergen
