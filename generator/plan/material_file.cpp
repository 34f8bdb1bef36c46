// A material description file (docs/user-guide.md "Material files") mapped onto MaterialBuilder
// calls, one call per JSON value, each carrying where the value stands so the builder's errors
// name it.
#include <string>
#include <vector>

#include "watergen/plan/json_reader.h"
#include "watergen/plan/material.h"

namespace watergen {

namespace {

// "axis=choice" of a rule's "if".
bool split_item(JsonReader& r, const std::string& pointer, std::string& axis, std::string& choice) {
    std::string item;
    if (!r.string(pointer, item)) return false;
    const size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size())
        return r.fail(pointer, "expected \"axis=choice\", got \"" + item + "\"");
    axis = item.substr(0, eq);
    choice = item.substr(eq + 1);
    return true;
}

// "axes": {"fresnel": ["schlick", "exact"], "shore": "all"}
bool read_axes(JsonReader& r, MaterialBuilder& b) {
    if (!r.object("/axes", "an object mapping axis names to choice lists")) return false;
    for (const std::string& axis : r.members("/axes")) {
        const std::string p = json_child("/axes", axis);
        const Json& value = r.at(p);
        if (value.is_string() && value.get<std::string>() == "all") {
            b.offer_all(axis, {&r.source(), p});
            continue;
        }
        std::vector<std::string> choices;
        if (!r.array(p, "an array of choices or \"all\"") || !r.strings(p, choices)) return false;
        b.offer(axis, choices, {&r.source(), p});
    }
    return true;
}

// {"if": "axis=choice", "requires" | "excludes": {"other_axis": [choices]}, "why": "..."}
bool read_rule(JsonReader& r, const std::string& p, MaterialBuilder& b) {
    if (!r.keys(p, {"if", "requires", "excludes", "why"}, {"if"})) return false;
    const bool is_requires = r.has(p + "/requires");
    if (is_requires == r.has(p + "/excludes"))
        return r.fail(p, "expected exactly one of 'requires' or 'excludes'");
    std::string axis, choice, why;
    if (!split_item(r, p + "/if", axis, choice)) return false;
    if (r.has(p + "/why") && !r.string(p + "/why", why)) return false;
    const std::string kp = p + (is_requires ? "/requires" : "/excludes");
    const Json& others = r.at(kp);
    if (!others.is_object() || others.empty())
        return r.fail(kp, "expected an object mapping an axis to a list of choices, e.g. "
                          "{\"waves\": [\"gerstner\"]}, got " +
                              json_describe(others));
    for (const std::string& other : r.members(kp)) {
        std::vector<std::string> choices;
        if (!r.strings(json_child(kp, other), choices)) return false;
        const SourceRef at{&r.source(), json_child(kp, other)};
        if (is_requires)
            b.requires_choice(axis, choice, other, choices, why, at);
        else
            b.excludes_choice(axis, choice, other, choices, why, at);
    }
    return true;
}

// "parameters": {"name": {"value": number | [numbers], "min": number, "max": number}}
bool read_parameters(JsonReader& r, MaterialBuilder& b) {
    if (!r.object("/parameters", "an object mapping parameter names to settings")) return false;
    for (const std::string& name : r.members("/parameters")) {
        const std::string p = json_child("/parameters", name);
        if (!r.keys(p, {"value", "min", "max"}, {})) return false;
        if (r.at(p).empty()) return r.fail(p, "expected at least one of 'value', 'min', 'max'");
        if (r.has(p + "/value")) {
            std::vector<double> v;
            if (!r.numbers(p + "/value", v)) return false;
            b.parameter(name, v, {&r.source(), p + "/value"});
        }
        const bool has_min = r.has(p + "/min");
        if (has_min != r.has(p + "/max"))
            return r.fail(p, std::string("missing key '") + (has_min ? "max" : "min") +
                                 "': a range needs both");
        if (has_min) {
            double lo = 0, hi = 0;
            if (!r.number(p + "/min", lo) || !r.number(p + "/max", hi)) return false;
            b.range(name, lo, hi, {&r.source(), p + "/min"});
        }
    }
    return true;
}

// Every key of the file as builder calls; false at the first value of the wrong shape.
bool read_material(JsonReader& r, MaterialBuilder& b) {
    std::string text;
    if (r.has("/description")) {
        if (!r.string("/description", text)) return false;
        b.description(text);
    }
    if (r.has("/preset")) {
        if (!r.string("/preset", text)) return false;
        b.preset(text, {&r.source(), "/preset"});
    }
    if (r.has("/axes") && !read_axes(r, b)) return false;
    if (r.has("/rules")) {
        if (!r.array("/rules", "an array of rules")) return false;
        for (size_t i = 0; i < r.at("/rules").size(); ++i)
            if (!read_rule(r, json_child("/rules", i), b)) return false;
    }
    if (r.has("/parameters") && !read_parameters(r, b)) return false;
    if (r.has("/targets")) {
        std::vector<std::string> targets;
        if (!r.strings("/targets", targets)) return false;
        b.targets(targets, {&r.source(), "/targets"});
    }
    return true;
}

} // namespace

std::optional<Material> parse_material(const JsonSource& src, Diagnostics& diagnostics) {
    JsonReader r(src, diagnostics);
    std::string name;
    if (!r.keys("", {"name", "description", "preset", "axes", "rules", "parameters", "targets"},
                {"name"}) ||
        !r.string("/name", name))
        return std::nullopt;
    MaterialBuilder b(name, {&src, "/name"});
    if (!read_material(r, b)) return std::nullopt;
    return b.build(diagnostics);
}

std::optional<Material> load_material(const std::filesystem::path& path, Diagnostics& diagnostics) {
    const auto src = load_json(path, diagnostics);
    return src ? parse_material(*src, diagnostics) : std::nullopt;
}

} // namespace watergen
