#include "watergen/plan/scene_file.h"

#include <algorithm>
#include <iterator>

#include <fmt/format.h>

#include "watergen/ir/text.h"
#include "watergen/plan/json_reader.h"

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
    const std::vector<std::string> allowed = {
        "name",          "description",  "shoreline",     "bottom_in_view",     "water_depth",
        "camera_height", "camera_pitch", "sun_elevation", "reflection_sources", "waves",
        "precision",     "platforms",    "fixed",         "scene_input"};
    // Optional: description, fixed, bottom_in_view (most scenes show their bottom) and
    // scene_input (most engines can give either).
    std::vector<std::string> required;
    std::copy_if(allowed.begin(), allowed.end(), std::back_inserter(required),
                 [](const std::string& k) {
                     return k != "description" && k != "fixed" && k != "bottom_in_view" &&
                            k != "scene_input";
                 });
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
    const NumberBounds depth{0.0, 1.2e4, "m"}, height{0.0, 1e5, "m"}, angle{-90.0, 90.0, "degrees"};
    std::string waves;
    const bool ok = r.boolean("/shoreline", s.shoreline) &&
                    r.range("/water_depth", s.water_depth.min, s.water_depth.max, &depth) &&
                    r.range("/camera_height", s.camera_height.min, s.camera_height.max, &height) &&
                    r.range("/camera_pitch", s.camera_pitch.min, s.camera_pitch.max, &angle) &&
                    r.range("/sun_elevation", s.sun_elevation.min, s.sun_elevation.max, &angle) &&
                    r.string_in("/waves", {"static", "animated"}, waves) &&
                    r.string_in("/precision", {"full", "half", "any"}, s.precision);
    if (!ok) return std::nullopt;
    if (r.has("/bottom_in_view") && !r.boolean("/bottom_in_view", s.bottom_in_view))
        return std::nullopt;
    if (r.has("/scene_input") &&
        !r.string_in("/scene_input", {"position_texture", "depth_buffer", "any"}, s.scene_input))
        return std::nullopt;
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
