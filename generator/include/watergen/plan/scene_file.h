// What a scene contains, as its description file states it: the facts scene pruning
// (scene_pruning.h) turns into skipped variants, constants and folded terms.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "watergen/ir/core/diagnostic.h"
#include "watergen/plan/json_reader.h"
#include "watergen/plan/json_source.h"
#include "watergen/plan/material.h"
#include "watergen/water/axis_registry.h"

namespace watergen {

struct FactRange {
    double min = 0.0, max = 0.0;
};

// Where to find each fact in the file, for explain ("open_ocean.json:4:3 /shoreline").
struct SceneWhere {
    struct Location {
        std::string file, pointer;
        JsonPosition position;
    };
    std::map<std::string, Location> fact; // JSON pointer without the leading '/' -> location
    std::string of(const std::string& key) const; // "file:line:col /key"
    Diagnostic error(const std::string& key, const std::string& what) const;
};

struct SceneFacts {
    std::string name; // also the scene's directory in the build output
    std::string description;
    std::string file;                            // the file's name (no directories), for reports
    bool shoreline = true;                       // water meets land somewhere in view
    bool bottom_in_view = true;                  // the refracted scene shows the bottom
    FactRange water_depth{0.0, 1e4};             // m, on water pixels
    FactRange camera_height{0.0, 1e5};           // m above the water level
    FactRange camera_pitch{-90, 90};             // degrees, negative looks down
    FactRange sun_elevation{-90, 90};            // degrees above the horizon
    std::vector<std::string> reflection_sources; // of kReflectionSources; empty = none
    bool waves_animated = true;
    std::string precision = "any"; // "full", "half" or "any"
    // How the engine gives the scene's position: "position_texture", "depth_buffer" or "any"
    // (the scene_input axis's choices; a scene may leave it out: any).
    std::string scene_input = "any";
    std::vector<std::string> platforms;               // of kPlatforms
    std::map<std::string, std::vector<double>> fixed; // parameters the scene fixes
    SceneWhere where;
};

// The keys of a scene file, in the order its errors list them: the one table the reader, the
// pruning's "where" and the manifest's scene facts read.
struct SceneKey {
    std::string_view key;
    bool required = true;
    // A range's bounds (water_depth, camera_height, camera_pitch, sun_elevation).
    std::optional<NumberBounds> bounds = std::nullopt;
    // The choices of a string key (waves, precision, scene_input), in the order errors list them.
    std::vector<std::string> choices = {};
    // The fact of a choice's scene needs (axis_registry.h) this key states; pruning names it.
    std::optional<SceneFact> fact = std::nullopt;
    // The key's value in the manifest's "facts" of a pruned scene; null: not recorded there.
    nlohmann::ordered_json (*manifest)(const SceneFacts&) = nullptr;
};
const std::vector<SceneKey>& scene_keys();
const SceneKey& scene_key(std::string_view key); // one of scene_keys(), or a logic error
// The key that states `fact`.
const SceneKey& scene_key(SceneFact fact);

// Vocabulary of the scene file (docs/user-guide.md "Scene files").
extern const std::vector<std::string> kReflectionSources; // planar, cubemap, horizon_map
extern const std::vector<std::string> kPlatforms;         // vulkan, d3d, opengl, gles, metal
// Targets a platform needs.
std::vector<Target> platform_targets(const std::string& platform);

// Reads a scene description. Errors name file, line, column, JSON path and what was
// expected. Parameters in "fixed" are checked against a material later (scene_pruning.h).
std::optional<SceneFacts> load_scene(const std::filesystem::path& path, Diagnostics& diagnostics);
std::optional<SceneFacts> parse_scene(const JsonSource& source, Diagnostics& diagnostics);

// The description files of a build: the material at `material_path` ("": the built-in default
// material) and each scene. False at the first file that does not load, its errors in
// `diagnostics`.
bool load_material_and_scenes(const std::string& material_path,
                              const std::vector<std::string>& scene_paths, Material& material,
                              std::vector<SceneFacts>& scenes, Diagnostics& diagnostics);

} // namespace watergen
