#include "watergen/plan/scene_file.h"

#include <algorithm>
#include <iterator>
#include <stdexcept>

#include <fmt/format.h>

#include "watergen/ir/core/text.h"
#include "watergen/plan/json_reader.h"

namespace watergen {

const std::vector<std::string> kReflectionSources = {"planar", "cubemap", "horizon_map"};
const std::vector<std::string> kPlatforms = {"vulkan", "d3d", "opengl", "gles", "metal"};

namespace {

using OJson = nlohmann::ordered_json;

OJson range_json(const FactRange& r) {
    return {r.min, r.max};
}

} // namespace

const std::vector<SceneKey>& scene_keys() {
    static const std::vector<SceneKey> keys = [] {
        const NumberBounds depth{0.0, 1.2e4, "m"}, height{0.0, 1e5, "m"};
        const NumberBounds angle{-90.0, 90.0, "degrees"};
        return std::vector<SceneKey>{
            {.key = "name"},
            {.key = "description", .required = false},
            {.key = "shoreline",
             .fact = SceneFact::Shoreline,
             .manifest = [](const SceneFacts& f) { return OJson(f.shoreline); }},
            // Optional: most scenes show their bottom.
            {.key = "bottom_in_view", .required = false, .fact = SceneFact::BottomInView},
            {.key = "water_depth",
             .bounds = depth,
             .fact = SceneFact::BottomLit,
             .manifest = [](const SceneFacts& f) { return range_json(f.water_depth); }},
            {.key = "camera_height",
             .bounds = height,
             .fact = SceneFact::CameraNear,
             .manifest = [](const SceneFacts& f) { return range_json(f.camera_height); }},
            {.key = "camera_pitch",
             .bounds = angle,
             .manifest = [](const SceneFacts& f) { return range_json(f.camera_pitch); }},
            {.key = "sun_elevation",
             .bounds = angle,
             .fact = SceneFact::SunAboveHorizon,
             .manifest = [](const SceneFacts& f) { return range_json(f.sun_elevation); }},
            {.key = "reflection_sources",
             .fact = SceneFact::ReflectionSource,
             .manifest = [](const SceneFacts& f) { return OJson(f.reflection_sources); }},
            {.key = "waves",
             .choices = {"static", "animated"},
             .manifest =
                 [](const SceneFacts& f) {
                     return OJson(f.waves_animated ? "animated" : "static");
                 }},
            {.key = "precision",
             .choices = {"full", "half", "any"},
             .fact = SceneFact::Precision,
             .manifest = [](const SceneFacts& f) { return OJson(f.precision); }},
            {.key = "platforms",
             .manifest = [](const SceneFacts& f) { return OJson(f.platforms); }},
            {.key = "fixed", .required = false},
            // Optional: most engines can give either. Recorded only when stated, so the scenes
            // that leave it out keep their manifest form.
            {.key = "scene_input",
             .required = false,
             .choices = {"position_texture", "depth_buffer", "any"},
             .fact = SceneFact::SceneInput,
             .manifest =
                 [](const SceneFacts& f) {
                     return f.scene_input == "any" ? OJson() : OJson(f.scene_input);
                 }},
        };
    }();
    return keys;
}

const SceneKey& scene_key(std::string_view key) {
    for (const SceneKey& k : scene_keys())
        if (k.key == key) return k;
    throw std::logic_error("no scene key '" + std::string(key) + "'");
}

const SceneKey& scene_key(SceneFact fact) {
    for (const SceneKey& k : scene_keys())
        if (k.fact == fact) return k;
    throw std::logic_error("no scene key states this fact");
}

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
    return Diagnostic{Severity::Error,   l.file, l.position.line,
                      l.position.column, "",     l.pointer + ": " + what};
}

std::optional<SceneFacts> parse_scene(const JsonSource& src, Diagnostics& ds) {
    SceneFacts s;
    s.file = std::filesystem::path(src.file()).filename().string();
    JsonReader r(src, ds);
    r.on_read([&](const std::string& pointer) {
        s.where.fact[pointer.substr(1)] = {src.file(), pointer, src.position(pointer)};
    });
    std::vector<std::string> allowed, required;
    for (const SceneKey& k : scene_keys()) {
        allowed.emplace_back(k.key);
        if (k.required) required.emplace_back(k.key);
    }
    // A material among the scenes: `build --scene a.json m.json` reads every file after
    // --scene as a scene.
    if (src.root().is_object() && src.root().contains("axes") && !src.root().contains("waves")) {
        ds.push_back(src.error("/axes",
                               "this is a material file (it offers \"axes\"), given where a scene "
                               "was expected: --scene takes every file after it, so name the "
                               "material before --scene"));
        return std::nullopt;
    }
    if (!r.keys("", allowed, required,
                "(a scene states every fact; see docs/user-guide.md \"Scene files\")"))
        return std::nullopt;
    if (!r.string("/name", s.name)) return std::nullopt;
    if (s.name.empty() ||
        s.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") != std::string::npos) {
        r.fail("/name",
               "scene name '" + s.name +
                   "': expected lower-case letters, digits, '_' or '-' (it names a directory)");
        return std::nullopt;
    }
    if (r.has("/description") && !r.string("/description", s.description)) return std::nullopt;
    auto range = [&](const char* key, FactRange& out) {
        return r.range(std::string("/") + key, out.min, out.max, &*scene_key(key).bounds);
    };
    auto choice = [&](const char* key, std::string& out) {
        return r.string_in(std::string("/") + key, scene_key(key).choices, out);
    };
    std::string waves;
    const bool ok = r.boolean("/shoreline", s.shoreline) && range("water_depth", s.water_depth) &&
                    range("camera_height", s.camera_height) &&
                    range("camera_pitch", s.camera_pitch) &&
                    range("sun_elevation", s.sun_elevation) && choice("waves", waves) &&
                    choice("precision", s.precision);
    if (!ok) return std::nullopt;
    if (r.has("/bottom_in_view") && !r.boolean("/bottom_in_view", s.bottom_in_view))
        return std::nullopt;
    if (r.has("/scene_input") && !choice("scene_input", s.scene_input)) return std::nullopt;
    s.waves_animated = waves == "animated";
    std::vector<std::string> sources_vocabulary = kReflectionSources;
    sources_vocabulary.push_back("none");
    if (!r.strings_in("/reflection_sources", sources_vocabulary, s.reflection_sources))
        return std::nullopt;
    if (std::find(s.reflection_sources.begin(), s.reflection_sources.end(), "none") !=
        s.reflection_sources.end()) {
        if (s.reflection_sources.size() > 1) {
            r.fail("/reflection_sources",
                   "'none' cannot be listed with a source; expected [\"none\"] or sources from " +
                       join(kReflectionSources));
            return std::nullopt;
        }
        s.reflection_sources.clear();
    }
    if (!r.strings_in("/platforms", kPlatforms, s.platforms)) return std::nullopt;
    if (s.platforms.empty()) {
        r.fail("/platforms", "no platform: the scene needs nothing; expected at least one of " +
                                 join(kPlatforms));
        return std::nullopt;
    }
    if (r.has("/fixed")) {
        if (!r.object("/fixed", "an object mapping parameter names to values")) return std::nullopt;
        for (const std::string& name : r.members("/fixed"))
            if (!r.numbers(json_child("/fixed", name), s.fixed[name], 1)) return std::nullopt;
    }
    return s;
}

std::optional<SceneFacts> load_scene(const std::filesystem::path& path, Diagnostics& ds) {
    const auto src = load_json(path, ds);
    return src ? parse_scene(*src, ds) : std::nullopt;
}

bool load_material_and_scenes(const std::string& material_path,
                              const std::vector<std::string>& scene_paths, Material& material,
                              std::vector<SceneFacts>& scenes, Diagnostics& ds) {
    if (material_path.empty()) {
        material = default_material();
    } else if (auto m = load_material(material_path, ds)) {
        material = std::move(*m);
    } else {
        return false;
    }
    for (const auto& path : scene_paths) {
        auto s = load_scene(path, ds);
        if (!s) return false;
        scenes.push_back(std::move(*s));
    }
    return true;
}

} // namespace watergen
