#include "watergen/plan/scene_file.h"

#include <algorithm>
#include <set>

#include <fmt/format.h>

namespace watergen {

const std::vector<std::string> kReflectionSources = {"planar", "cubemap", "horizon_map"};
const std::vector<std::string> kPlatforms = {"vulkan", "d3d", "opengl", "gles", "metal"};

std::vector<Target> platform_targets(const std::string& platform) {
    // SPIR-V consumers get the module and its reflection; the others get their language.
    if (platform == "vulkan") return {Target::Glsl, Target::Spirv, Target::Reflection};
    if (platform == "d3d") return {Target::Hlsl, Target::Spirv, Target::Reflection};
    if (platform == "opengl") return {Target::Glsl330};
    if (platform == "gles") return {Target::Essl300};
    if (platform == "metal") return {Target::Msl};
    return {};
}

std::string SceneWhere::of(const std::string& key) const {
    auto it = fact.find(key);
    if (it == fact.end()) return "";
    const Location& l = it->second;
    return fmt::format("{}:{}:{} {}", l.file, l.position.line, l.position.column, l.pointer);
}

Diagnostic SceneWhere::error(const std::string& key, const std::string& what) const {
    auto it = fact.find(key);
    if (it == fact.end()) return Diagnostic{Severity::Error, "", 0, 0, "", what};
    const Location& l = it->second;
    return Diagnostic{Severity::Error, l.file, l.position.line, l.position.column, "", l.pointer + ": " + what};
}

namespace {

std::string join(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

class SceneReader {
public:
    SceneReader(const JsonSource& src, Diagnostics& ds, SceneFacts& out) : src_(src), ds_(ds), out_(out) {}

    bool fail(const std::string& pointer, const std::string& what) {
        ds_.push_back(src_.error(pointer, what));
        return false;
    }
    const Json& at(const std::string& pointer) { return src_.root().at(Json::json_pointer(pointer)); }
    void locate(const std::string& pointer) {
        out_.where.fact[pointer.substr(1)] = {src_.file(), pointer, src_.position(pointer)};
    }

    bool string(const std::string& pointer, std::string& s) {
        const Json& v = at(pointer);
        if (!v.is_string()) return fail(pointer, "expected a string, got " + json_describe(v));
        s = v.get<std::string>();
        locate(pointer);
        return true;
    }
    bool one_of(const std::string& pointer, const std::vector<std::string>& allowed, std::string& s) {
        if (!string(pointer, s)) return false;
        if (std::find(allowed.begin(), allowed.end(), s) == allowed.end())
            return fail(pointer, "unknown value '" + s + "'; expected one of " + join(allowed));
        return true;
    }
    bool boolean(const std::string& pointer, bool& b) {
        const Json& v = at(pointer);
        if (!v.is_boolean()) return fail(pointer, "expected true or false, got " + json_describe(v));
        b = v.get<bool>();
        locate(pointer);
        return true;
    }
    bool number(const std::string& pointer, double& x) {
        const Json& v = at(pointer);
        if (!v.is_number()) return fail(pointer, "expected a number, got " + json_describe(v));
        x = v.get<double>();
        locate(pointer);
        return true;
    }
    // {"min": a, "max": b} within [lo, hi] of the fact's domain.
    bool range(const std::string& pointer, double lo, double hi, const char* unit, FactRange& r) {
        const Json& v = at(pointer);
        if (!v.is_object()) return fail(pointer, "expected an object {\"min\": number, \"max\": number}, got " + json_describe(v));
        for (const auto& [k, _] : v.items())
            if (k != "min" && k != "max") return fail(json_child(pointer, k), "unknown key '" + k + "'; expected min or max");
        for (const char* k : {"min", "max"})
            if (!v.contains(k)) return fail(pointer, std::string("missing key '") + k + "'");
        if (!number(pointer + "/min", r.min) || !number(pointer + "/max", r.max)) return false;
        locate(pointer);
        for (const auto& [k, x] : {std::pair{"min", r.min}, std::pair{"max", r.max}})
            if (x < lo || x > hi)
                return fail(pointer + "/" + k, fmt::format("{:g} {} is out of range; expected a value in [{:g}, {:g}] {}", x, unit, lo, hi, unit));
        if (r.min > r.max) return fail(pointer, fmt::format("min {:g} is above max {:g}; expected min <= max", r.min, r.max));
        return true;
    }
    bool list(const std::string& pointer, const std::vector<std::string>& allowed, std::vector<std::string>& out) {
        const Json& v = at(pointer);
        if (!v.is_array()) return fail(pointer, "expected an array of strings (" + join(allowed) + "), got " + json_describe(v));
        locate(pointer);
        std::set<std::string> seen;
        for (size_t i = 0; i < v.size(); ++i) {
            std::string s;
            if (!one_of(json_child(pointer, i), allowed, s)) return false;
            if (!seen.insert(s).second) return fail(json_child(pointer, i), "'" + s + "' is listed twice");
            out.push_back(s);
        }
        return true;
    }

private:
    const JsonSource& src_;
    Diagnostics& ds_;
    SceneFacts& out_;
};

} // namespace

std::optional<SceneFacts> parse_scene(const JsonSource& src, Diagnostics& ds) {
    SceneFacts s;
    s.file = std::filesystem::path(src.file()).filename().string();
    SceneReader r(src, ds, s);
    const Json& doc = src.root();
    const std::vector<std::string> allowed = {"name", "description", "shoreline", "water_depth", "camera_height",
                                              "camera_pitch", "sun_elevation", "reflection_sources", "waves",
                                              "precision", "platforms", "fixed"};
    if (!doc.is_object()) {
        r.fail("", "expected an object with keys " + join(allowed) + ", got " + json_describe(doc));
        return std::nullopt;
    }
    for (const auto& [k, _] : doc.items())
        if (std::find(allowed.begin(), allowed.end(), k) == allowed.end()) {
            r.fail(json_child("", k), "unknown key '" + k + "'; expected one of " + join(allowed));
            return std::nullopt;
        }
    for (const auto& k : allowed)
        if (k != "description" && k != "fixed" && !doc.contains(k)) {
            r.fail("", "missing key '" + k + "' (a scene states every fact; see README \"Scene files\")");
            return std::nullopt;
        }
    if (!r.string("/name", s.name)) return std::nullopt;
    if (s.name.empty() || s.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") != std::string::npos) {
        r.fail("/name", "scene name '" + s.name + "': expected lower-case letters, digits, '_' or '-' (it names a directory)");
        return std::nullopt;
    }
    if (doc.contains("description") && !r.string("/description", s.description)) return std::nullopt;
    std::string waves;
    const bool ok = r.boolean("/shoreline", s.shoreline) && r.range("/water_depth", 0.0, 1.2e4, "m", s.water_depth) &&
                    r.range("/camera_height", 0.0, 1e5, "m", s.camera_height) &&
                    r.range("/camera_pitch", -90.0, 90.0, "degrees", s.camera_pitch) &&
                    r.range("/sun_elevation", -90.0, 90.0, "degrees", s.sun_elevation) &&
                    r.one_of("/waves", {"static", "animated"}, waves) &&
                    r.one_of("/precision", {"full", "half", "any"}, s.precision);
    if (!ok) return std::nullopt;
    s.waves_animated = waves == "animated";
    std::vector<std::string> sources_vocabulary = kReflectionSources;
    sources_vocabulary.push_back("none");
    if (!r.list("/reflection_sources", sources_vocabulary, s.reflection_sources)) return std::nullopt;
    if (std::find(s.reflection_sources.begin(), s.reflection_sources.end(), "none") != s.reflection_sources.end()) {
        if (s.reflection_sources.size() > 1) {
            r.fail("/reflection_sources", "'none' cannot be listed with a source; expected [\"none\"] or sources from " +
                                              join(kReflectionSources));
            return std::nullopt;
        }
        s.reflection_sources.clear();
    }
    if (!r.list("/platforms", kPlatforms, s.platforms)) return std::nullopt;
    if (s.platforms.empty()) {
        r.fail("/platforms", "no platform: the scene needs nothing; expected at least one of " + join(kPlatforms));
        return std::nullopt;
    }
    if (doc.contains("fixed")) {
        const Json& f = doc["fixed"];
        if (!f.is_object()) {
            r.fail("/fixed", "expected an object mapping parameter names to values, got " + json_describe(f));
            return std::nullopt;
        }
        for (const auto& [name, value] : f.items()) {
            const std::string p = json_child("/fixed", name);
            std::vector<double> v;
            if (value.is_number()) {
                double x = 0;
                if (!r.number(p, x)) return std::nullopt;
                v = {x};
            } else if (value.is_array() && !value.empty()) {
                for (size_t i = 0; i < value.size(); ++i) {
                    double x = 0;
                    if (!r.number(json_child(p, i), x)) return std::nullopt;
                    v.push_back(x);
                }
                r.locate(p);
            } else {
                r.fail(p, "expected a number or an array of numbers, got " + json_describe(value));
                return std::nullopt;
            }
            s.fixed[name] = v;
        }
    }
    return s;
}

std::optional<SceneFacts> load_scene(const std::filesystem::path& path, Diagnostics& ds) {
    Diagnostic error;
    const auto src = JsonSource::load(path, &error);
    if (!src) {
        ds.push_back(error);
        return std::nullopt;
    }
    return parse_scene(*src, ds);
}

} // namespace watergen
