// The engine's view of a `watergen build` output directory: manifest.json plus one directory per
// shader. Opens the manifest, lists the variants, selects one (by choices, by scene and feature
// choices, or by a runtime key) and hands out the bytes of its files and its reflection.
// Part of watergen::runtime (the library an engine links): no generator, no glslang.
//
// Errors are data: nothing here throws. A failed call returns std::nullopt (or an empty
// result) and sets `error` to "<file>: <key path>: what was expected".
//
// Selection rule (select()):
//  - The request names a scene (may be empty when the build has exactly one) and a choice for
//    some or all axes ("foam" -> "shore"). Every named axis and choice must exist in the
//    material; an unknown one is always an error.
//  - The variants of the scene whose choices match every named axis are candidates. Exactly one:
//    it is the result. Several (a partial request): an error naming the axes that still differ,
//    with Fallback::Error; the first in manifest order (sorted by key) with NearestKept.
//  - None (the scene pruned the combination): with Fallback::Error (the default) an error naming
//    each requested choice the scene does not keep, or, when each is kept alone, the
//    combination. With Fallback::NearestKept the kept variant that changes the fewest named
//    axes (ties: manifest order), and `changed` says which, e.g. "foam: shore -> none".
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "watergen/runtime/binding_layout.h"
#include "watergen/runtime/build_pass.h"
#include "watergen/runtime/host_values.h"
#include "watergen/runtime/reflection.h"

namespace watergen {

// One parameter of a variant's uniform block as the manifest declares it (the generator's
// interface, before any compiler dropped unread members).
struct BlockParameter {
    std::string name;
    std::string type;        // float, vec2, vec3, vec4, int, uint
    uint32_t array_size = 0; // 0: not an array
    uint32_t offset = 0;     // where the generator placed it (valid for std140 and cbuffer)
    std::vector<double> default_value;
    double min = 0, max = 0;
    HostValue host{}; // how the host makes the value the shader reads (host_values.h)
};

struct TextureSlot {
    std::string name;
    uint32_t binding = 0;
    std::string type; // texture2D, textureCube
};

// How a mesh variant (geometry=mesh or tessellated) is drawn: its stages, its vertex layout
// (attribute i at location i, interleaved floats) and its topology. The grid comes from
// water_grid() (water_grid.h), whose vertices have exactly this layout.
struct VertexInput {
    std::string name; // "grid_xz", "grid_lod"
    uint32_t location = 0, floats = 0, offset = 0;
};
struct VariantGeometry {
    std::string name;                // "mesh" or "tessellated"
    std::vector<std::string> stages; // "vertex", ["tess_control", "tess_evaluation",] "fragment"
    std::vector<VertexInput> vertex_inputs;
    uint32_t vertex_stride = 0;        // bytes
    uint32_t patch_control_points = 0; // 4 for tessellated; 0: a triangle list
    bool tessellated() const { return patch_control_points > 0; }
    std::vector<uint32_t> attribute_sizes() const; // floats per input, location order
};

struct BuildVariant {
    std::string scene;
    std::string key;                            // "fresnel=schlick,extinction=absorb_scatter,..."
    std::string hash;                           // short hash, also accepted as a runtime key
    std::map<std::string, std::string> choices; // axis -> choice
    std::string shader_directory;               // relative to the build directory
    // Files per kind ("spirv", "glsl", "hlsl", "glsl330", "essl300", "msl", "reflection",
    // "description"), paths relative to the build directory, as the manifest lists them.
    std::map<std::string, std::vector<std::string>> files;
    std::string block_name; // uniform block ("WaterParams"); "" without one
    std::vector<BlockParameter> parameters;
    std::vector<TextureSlot> textures;
    // Parameters the scene folded into the shader as constants, with the folded value.
    std::map<std::string, std::vector<double>> folded_parameters;
    // Parameters the shader no longer reads (folded, or their term was removed).
    std::vector<std::string> removed_parameters;
    // Specialized / branching build modes: the variant's selector values, by constant id and by
    // block member name (the uniform writer sets the latter).
    std::map<uint32_t, double> specialization;
    std::map<std::string, double> selector_uniforms;
    // Specialized mode with freeze: the variant's own fragment SPIR-V per language.
    std::map<std::string, std::string> frozen;
    // Companion passes the variant needs, by name ("caustics"); ShaderBuild::pass() opens one.
    std::map<std::string, PassReference> passes;
    // The stem of the shader's files: "<lang>/<stem>.<stage>...". "water"; a pass's "caustics".
    std::string file_stem = "water";
    // A mesh variant's (the manifest's "geometry"); none for the fullscreen screen pass.
    std::optional<VariantGeometry> geometry;
};

// A companion pass opened: the manifest's reference, and the pass as a shader (directory,
// files, its uniform block from pass.json with the scene's values as folded parameters, so a
// UniformWriter starts at them and refuses others) for spirv(), source(), reflection() and
// UniformWriter.
struct BuildPass {
    std::string name; // "caustics"
    PassReference reference;
    BuildVariant shader;
};

enum class Fallback { Error, NearestKept };

struct Selection {
    const BuildVariant* variant = nullptr; // null on error
    std::vector<std::string> changed;      // NearestKept: "axis: asked -> kept", one per axis
    std::string error;
    bool ok() const { return variant != nullptr; }
};

class ShaderBuild {
  public:
    // Reads <directory>/manifest.json. Errors name the file and the JSON key.
    static std::optional<ShaderBuild> open(const std::filesystem::path& directory,
                                           std::string* error);

    const std::filesystem::path& directory() const { return directory_; }
    const std::string& generator() const { return generator_; } // "watergen 0.1.0"
    const std::string& mode() const { return mode_; }           // "permutations", ...
    const std::vector<std::string>& scenes() const { return scenes_; }
    // Axis -> choices of the material, in the material's order.
    const std::map<std::string, std::vector<std::string>>& axes() const { return axes_; }
    const std::vector<BuildVariant>& variants() const { return variants_; } // (scene, key) order
    // The binding map every shader of the build was emitted with (manifest "bindings"): make
    // one BindingLayout of it for all their pipelines. Empty for a manifest without one.
    const BuildBindings& bindings() const { return bindings_; }

    Selection select(const std::string& scene, const std::map<std::string, std::string>& choices,
                     Fallback fallback = Fallback::Error) const;
    // A runtime key: the variant's key string ("fresnel=schlick,...", every axis or some) or its
    // short hash. Same rule as select().
    Selection select_key(const std::string& scene, const std::string& key,
                         Fallback fallback = Fallback::Error) const;

    // Bytes of a file the manifest lists (a path relative to the build directory). Refuses
    // absolute paths, "..", and files the manifest does not list.
    std::optional<std::string> read(const std::string& relative_path, std::string* error) const;

    // The variant's (or a pass's shader's) SPIR-V of one language path ("glsl" or "hlsl") and
    // stage: the optimised module ("<lang>/<file_stem>.<stage>.opt.spv"); for the fragment stage of
    // a frozen specialized build, the variant's frozen module. Checked before it is returned
    // (spirv_check.h): check_spirv() for the stage's execution model, then spirv-val; a module
    // that fails either is an error naming the file and what was expected.
    std::optional<std::vector<uint32_t>> spirv(const BuildVariant& v, const std::string& language,
                                               ShaderStage stage, std::string* error) const;
    // The file of kind `kind` for `stage` ("glsl", "hlsl", "glsl330", "essl300", "msl"), as text.
    std::optional<std::string> source(const BuildVariant& v, const std::string& kind,
                                      ShaderStage stage, std::string* error) const;
    // "<lang>/<file_stem>.<stage>.reflect.json", parsed.
    std::optional<Reflection> reflection(const BuildVariant& v, const std::string& language,
                                         ShaderStage stage, std::string* error) const;

    // The companion pass `name` of a variant (BuildVariant::passes), its pass.json read. Errors
    // name the file and key: a variant without that pass, a malformed pass.json.
    std::optional<BuildPass> pass(const BuildVariant& v, const std::string& name,
                                  std::string* error) const;

  private:
    std::optional<std::string> listed(const BuildVariant& v, const std::string& kind,
                                      const std::string& suffix, std::uintmax_t max_bytes,
                                      std::string* error) const;
    // read() with a size limit of the file's kind (SPIR-V, reflection, pass.json).
    std::optional<std::string> read_at_most(const std::string& relative_path,
                                            std::uintmax_t max_bytes, std::string* error) const;

    std::filesystem::path directory_;
    std::string generator_, mode_ = "permutations";
    std::vector<std::string> scenes_;
    std::map<std::string, std::vector<std::string>> axes_;
    std::vector<BuildVariant> variants_;
    BuildBindings bindings_;
};

} // namespace watergen
