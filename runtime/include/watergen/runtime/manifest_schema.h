// The schema of a build's manifest.json, in one place: every key the generator writes, as a named
// constant grouped by the object that holds it, and a table of every key path it can write with
// the key's JSON type and the programs that read it. The writer (generator/pipeline/manifest,
// and generator/pipeline/variant for the parts of variant.json the manifest copies), watergen
// merge (generator/pipeline/shards), the build's C++ header (generator/pipeline/record/
// shaders_header.cpp), the generator's checks of an output directory and the runtime's reader
// (runtime/src/shader_build.cpp, manifest_reader.cpp, build_pass.cpp) spell the keys with these
// constants. tests/pipeline/manifest_schema_test.cpp holds the table to the checked-in build
// (generated/manifest.json) and to the readers it names (all but the merge: each reads what the
// table says it reads, and nothing else), tests/pipeline/build_modes_test.cpp to the specialized
// and branching builds' manifests. Header only, no JSON library: part of watergen::runtime,
// which the generator's pipeline may include (tests/layout).
//
// The keys are `const char[]` constants: they go wherever their literals went (nlohmann's
// operator[] and value(), std::string concatenation, std::set<std::string> initialisers, the
// runtime reader's `const char*` keys) and convert to std::string_view where one is wanted.
//
// The manifest states no format version. Its first member, "generator", is "watergen <version>"
// (kGeneratorPrefix and the generator's version): the runtime and the generator's output checks
// take a document that begins so for a manifest. The keys a manifest holds depend on the build's
// mode (the specialized and branching modes write "mode" and "shaders"; a permutations build
// neither) and on its variants (a mesh variant's "geometry", a caustics variant's "passes").
#pragma once

#include <string_view>

namespace watergen::manifest_schema {

// The document's members, in the order the writer writes them; "mode" and "shaders" in the
// specialized and branching modes only.
namespace top {
inline constexpr char kGenerator[] = "generator"; // string: kGeneratorPrefix + the version
inline constexpr char kMaterial[] = "material";   // object: the material (namespace material)
inline constexpr char kSpace[] = "space";         // object: variant counts (namespace space)
inline constexpr char kScenes[] = "scenes";       // array of objects (namespace scene)
inline constexpr char kBindings[] = "bindings";   // object: the binding map (namespace bindings)
inline constexpr char kMode[] = "mode";           // string: "specialized" or "branching"
inline constexpr char kShaders[] = "shaders";     // array of objects (namespace shader)
inline constexpr char kVariants[] = "variants";   // array of objects (namespace variant)
// The start of "generator"'s value: "watergen " and the version ("watergen 0.1.0").
inline constexpr char kGeneratorPrefix[] = "watergen ";
} // namespace top

// "material".
namespace material {
inline constexpr char kName[] = "name";               // string
inline constexpr char kDescription[] = "description"; // string
inline constexpr char kPreset[] = "preset";           // string
inline constexpr char kAxes[] = "axes";               // map: axis -> array of choice strings
inline constexpr char kRules[] = "rules";             // array of objects (namespace rule)
inline constexpr char kParameters[] = "parameters";   // map: parameter -> object (parameter)
inline constexpr char kTargets[] = "targets";         // array of target strings
} // namespace material

// An element of "material"."rules": "if" "axis=choice", then "requires" or "excludes", then "why".
namespace rule {
inline constexpr char kIf[] = "if";             // string
inline constexpr char kRequires[] = "requires"; // map: axis -> array of choice strings
inline constexpr char kExcludes[] = "excludes"; // map: axis -> array of choice strings
inline constexpr char kWhy[] = "why";           // string
} // namespace rule

// A value of "material"."parameters": what the material sets (each key only when it does).
namespace parameter {
inline constexpr char kValue[] = "value"; // array of numbers
inline constexpr char kMin[] = "min";     // number
inline constexpr char kMax[] = "max";     // number
} // namespace parameter

// "space".
namespace space {
inline constexpr char kFull[] = "full";         // unsigned: variants of the full space
inline constexpr char kMaterial[] = "material"; // unsigned: variants of the material's space
} // namespace space

// An element of "scenes". An unpruned build's one scene has "name", "pruned" (false) and
// "variants" only.
namespace scene {
inline constexpr char kName[] = "name";               // string
inline constexpr char kPruned[] = "pruned";           // bool
inline constexpr char kDescription[] = "description"; // string
inline constexpr char kFile[] = "file";               // string: the scene file's name
// object: the scene file's facts, keyed as the scene file is (generator/plan/scene_file.cpp's
// scene_keys(), which writes them)
inline constexpr char kFacts[] = "facts";
inline constexpr char kVariants[] = "variants"; // unsigned: the variants the scene keeps
inline constexpr char kSkipped[] = "skipped";   // unsigned: the variants it prunes
inline constexpr char kFixed[] = "fixed";       // map: parameter -> array of numbers
inline constexpr char kTargets[] = "targets";   // array of target strings
} // namespace scene

// "bindings": the map's name and its resources, as a binding map file spells them
// (generator/plan/binding_map_file.cpp's binding_map_json(), which writes them).
namespace bindings {
inline constexpr char kMap[] = "map";             // string: a profile's name or the file's
inline constexpr char kResources[] = "resources"; // map: resource name -> object (resource)
// unsigned: the push-constant range's bytes, with a push_constant resource only
inline constexpr char kPushConstantBytes[] = "push_constant_bytes";
} // namespace bindings

// A value of "bindings"."resources". A push constant has no set, binding or HLSL slot.
namespace resource {
// string: "uniform_block", "sampler", "texture" or "push_constant"
inline constexpr char kKind[] = "kind";
inline constexpr char kSet[] = "set";                    // unsigned
inline constexpr char kBinding[] = "binding";            // unsigned
inline constexpr char kHlslRegister[] = "hlsl_register"; // unsigned
inline constexpr char kHlslSpace[] = "hlsl_space";       // unsigned
inline constexpr char kMsl[] = "msl";                    // unsigned: the Metal index
inline constexpr char kGl[] = "gl";                      // unsigned: the GL binding or unit
} // namespace resource

// An element of "variants". A permutations build's: scene, key, hash, content_hash, nodes, the
// fold (namespace fold), the output (namespace output), passes. A specialized or branching
// build's: scene, key, hash, shader, nodes, selectors, specialization_constants (specialized) or
// uniforms (branching), frozen (specialized with freeze), passes.
namespace variant {
inline constexpr char kScene[] = "scene";              // string
inline constexpr char kKey[] = "key";                  // string: "axis=choice,..."
inline constexpr char kHash[] = "hash";                // string: the key's short hash
inline constexpr char kContentHash[] = "content_hash"; // string: the files' cache key
inline constexpr char kShader[] = "shader";            // string: the directory of its shader
inline constexpr char kNodes[] = "nodes";              // map: axis -> "axis.choice"
inline constexpr char kSelectors[] = "selectors";      // map: selector parameter -> number
// array of objects (namespace placed)
inline constexpr char kSpecializationConstants[] = "specialization_constants";
inline constexpr char kUniforms[] = "uniforms"; // array of objects (placed)
inline constexpr char kFrozen[] = "frozen";     // map: language -> SPIR-V path
inline constexpr char kPasses[] = "passes";     // object (namespace passes)
} // namespace variant

// An element of "shaders" (a switched shader built): scene, key, content_hash, axes, the output
// (namespace output), selectors, variants, the fold (namespace fold).
namespace shader {
inline constexpr char kScene[] = "scene";              // string
inline constexpr char kKey[] = "key";                  // string: "axis=choice|choice,..."
inline constexpr char kContentHash[] = "content_hash"; // string: the files' cache key
inline constexpr char kAxes[] = "axes";                // map: axis -> array of offered choices
inline constexpr char kSelectors[] = "selectors";      // array of objects (namespace selector)
inline constexpr char kVariants[] = "variants";        // unsigned: the variants it draws
} // namespace shader

// What a built entry (a permutations variant, a shader) says of its files, in this order.
namespace output {
// string: the key of the entry of the same scene whose files it shares; only then
inline constexpr char kSameAs[] = "same_as";
inline constexpr char kDirectory[] = "directory";   // string: relative to the build directory
inline constexpr char kFiles[] = "files";           // object (namespace files)
inline constexpr char kReflection[] = "reflection"; // object (namespace reflection)
// map: language -> object (namespace instructions)
inline constexpr char kSpirvInstructions[] = "spirv_instructions";
inline constexpr char kGeometry[] = "geometry"; // object (namespace geometry); a mesh variant's
} // namespace output

// What folding did to a built entry's shader (the fold's own keys only when it folded).
namespace fold {
inline constexpr char kFoldedParameters[] = "folded_parameters";   // map: parameter -> numbers
inline constexpr char kRemovedParameters[] = "removed_parameters"; // array of objects (removed)
inline constexpr char kRemovedTextures[] = "removed_textures";     // array of objects (removed)
inline constexpr char kRemovedTerms[] = "removed_terms";           // array of objects (removed)
inline constexpr char kLiveIrNodes[] = "live_ir_nodes"; // object (namespace live_ir_nodes)
} // namespace fold

// An element of "removed_parameters", "removed_textures" ("name", "because") or
// "removed_terms" ("node", "term", "because").
namespace removed {
inline constexpr char kName[] = "name";       // string
inline constexpr char kNode[] = "node";       // string
inline constexpr char kTerm[] = "term";       // string
inline constexpr char kBecause[] = "because"; // array of fact texts
} // namespace removed

// "live_ir_nodes".
namespace live_ir_nodes {
inline constexpr char kBefore[] = "before"; // unsigned
inline constexpr char kAfter[] = "after";   // unsigned
} // namespace live_ir_nodes

// An element of a shader's "selectors": "constant_id" (specialized) or "offset" (branching),
// unless the shader no longer reads the selector.
namespace selector {
inline constexpr char kAxis[] = "axis";              // string
inline constexpr char kParameter[] = "parameter";    // string: the selector's parameter
inline constexpr char kChoices[] = "choices";        // array of choice strings
inline constexpr char kConstantId[] = "constant_id"; // unsigned
inline constexpr char kOffset[] = "offset";          // unsigned: in the uniform block
} // namespace selector

// An element of a served variant's "specialization_constants" ("id", "name", "value") or
// "uniforms" ("name", "offset", "value").
namespace placed {
inline constexpr char kId[] = "id";         // unsigned: the constant id
inline constexpr char kName[] = "name";     // string: the selector's parameter
inline constexpr char kOffset[] = "offset"; // unsigned: in the uniform block
inline constexpr char kValue[] = "value";   // number
} // namespace placed

// "files" (an entry's or a pass's): each kind with files, in this order, an array of paths
// relative to the build directory.
namespace files {
inline constexpr char kDescription[] = "description"; // variant.json or pass.json
inline constexpr char kGlsl[] = "glsl";
inline constexpr char kHlsl[] = "hlsl";
inline constexpr char kSpirv[] = "spirv";
inline constexpr char kGlsl330[] = "glsl330";
inline constexpr char kEssl300[] = "essl300";
inline constexpr char kMsl[] = "msl";
inline constexpr char kReflection[] = "reflection"; // *.reflect.json
} // namespace files

// "reflection": the parts of the entry's variant.json the manifest copies (variant.json has
// them at its top level, under the same keys).
namespace reflection {
inline constexpr char kUniformBlock[] = "uniform_block"; // object (namespace uniform_block)
inline constexpr char kSampler[] = "sampler";            // object (namespace sampler); or {}
inline constexpr char kTextures[] = "textures";          // array of objects (namespace texture)
// array of objects (namespace member, "constant_ids" for "offset"); only with some
inline constexpr char kSpecializationConstants[] = "specialization_constants";
} // namespace reflection

// "uniform_block": "push_constant" for "set" and "binding" when the map makes it one.
namespace uniform_block {
inline constexpr char kName[] = "name";                  // string
inline constexpr char kSet[] = "set";                    // unsigned
inline constexpr char kBinding[] = "binding";            // unsigned
inline constexpr char kPushConstant[] = "push_constant"; // bool: true
inline constexpr char kSize[] = "size";                  // unsigned: bytes
inline constexpr char kMembers[] = "members";            // array of objects (namespace member)
} // namespace uniform_block

// A member of a uniform block, or a specialization constant: a parameter and its place.
namespace member {
inline constexpr char kName[] = "name";                // string
inline constexpr char kType[] = "type";                // string: float, vec2, ...
inline constexpr char kOffset[] = "offset";            // unsigned: a block member's place
inline constexpr char kConstantIds[] = "constant_ids"; // array of unsigned: a constant's place
inline constexpr char kDefault[] = "default";          // array of numbers (all elements)
inline constexpr char kMin[] = "min";                  // number
inline constexpr char kMax[] = "max";                  // number
inline constexpr char kUnit[] = "unit";                // string
inline constexpr char kSeed[] = "seed";                // string: the seed's section
inline constexpr char kNode[] = "node";                // string: the node that declares it
inline constexpr char kArraySize[] = "array_size";     // unsigned: an array's only
inline constexpr char kArrayStride[] = "array_stride"; // unsigned: an array's only
inline constexpr char kHost[] = "host"; // object (namespace host): how the host makes the value
} // namespace member

// A member's "host" (runtime/host_values.h); absent for a value the shader reads as set.
namespace host {
inline constexpr char kRule[] = "rule";     // string: host_rule_name
inline constexpr char kInputs[] = "inputs"; // array of parameter strings the rule reads
} // namespace host

// "sampler".
namespace sampler {
inline constexpr char kName[] = "name";       // string
inline constexpr char kSet[] = "set";         // unsigned
inline constexpr char kBinding[] = "binding"; // unsigned
} // namespace sampler

// An element of "textures".
namespace texture {
inline constexpr char kName[] = "name";       // string
inline constexpr char kSet[] = "set";         // unsigned
inline constexpr char kBinding[] = "binding"; // unsigned
inline constexpr char kType[] = "type";       // string: texture2D, textureCube
} // namespace texture

// A value of "spirv_instructions" (per language), unsigned counts; the patch stages' with
// tessellation only.
namespace instructions {
inline constexpr char kFragment[] = "fragment";
inline constexpr char kFragmentOptimized[] = "fragment_optimized";
inline constexpr char kVertex[] = "vertex";
inline constexpr char kTessControl[] = "tess_control";
inline constexpr char kTessEvaluation[] = "tess_evaluation";
} // namespace instructions

// "geometry" (geometry=mesh or tessellated): "patch_control_points" and "tessellation" with
// tessellation only.
namespace geometry {
inline constexpr char kName[] = "name";                  // string: "mesh", "tessellated"
inline constexpr char kStages[] = "stages";              // array of stage strings
inline constexpr char kTopology[] = "topology";          // string
inline constexpr char kVertexStride[] = "vertex_stride"; // unsigned: bytes
inline constexpr char kVertexInputs[] = "vertex_inputs"; // array of objects (vertex_input)
inline constexpr char kGrid[] = "grid";                  // object (namespace grid)
inline constexpr char kFrontFace[] = "front_face";       // string
inline constexpr char kPatchControlPoints[] = "patch_control_points"; // unsigned: 4
inline constexpr char kTessellation[] = "tessellation"; // object (namespace tessellation)
} // namespace geometry

// An element of "vertex_inputs".
namespace vertex_input {
inline constexpr char kName[] = "name";         // string
inline constexpr char kLocation[] = "location"; // unsigned
inline constexpr char kFloats[] = "floats";     // unsigned
inline constexpr char kOffset[] = "offset";     // unsigned: bytes
} // namespace vertex_input

// "grid".
namespace grid {
inline constexpr char kKind[] = "kind";             // string
inline constexpr char kMadeBy[] = "made_by";        // string
inline constexpr char kParameters[] = "parameters"; // array of parameter strings
} // namespace grid

// "tessellation".
namespace tessellation {
inline constexpr char kMaxFactor[] = "max_factor";  // number
inline constexpr char kParameters[] = "parameters"; // array of parameter strings
} // namespace tessellation

// "passes": a variant's companion passes by name.
namespace passes {
inline constexpr char kCaustics[] = "caustics"; // object (namespace pass)
} // namespace passes

// A pass of "passes".
namespace pass {
inline constexpr char kMethod[] = "method";        // string: "area_ratio", "photon_splat"
inline constexpr char kWaveModel[] = "wave_model"; // string
inline constexpr char kDirectory[] = "directory";  // string: relative to the build directory
inline constexpr char kFiles[] = "files";          // object (namespace files)
inline constexpr char kDraw[] = "draw";            // object (namespace draw)
inline constexpr char kValues[] = "values";        // map: parameter -> array of numbers
} // namespace pass

// A pass's "draw" (runtime/include/watergen/runtime/build_pass.h): "photon_share" for points
// only.
namespace draw {
inline constexpr char kPrimitive[] = "primitive";           // string: "triangles", "points"
inline constexpr char kAttribute[] = "attribute";           // string
inline constexpr char kCellsPerTexel[] = "cells_per_texel"; // unsigned
inline constexpr char kMargin[] = "margin";                 // object (namespace margin)
inline constexpr char kWindow[] = "window";                 // string: a parameter
inline constexpr char kTexels[] = "texels";                 // unsigned
inline constexpr char kFormat[] = "format";                 // string
inline constexpr char kChannel[] = "channel";               // string
inline constexpr char kClear[] = "clear";                   // number
inline constexpr char kBlend[] = "blend";                   // string
inline constexpr char kPhotonShare[] = "photon_share";      // string: a parameter
} // namespace draw

// A draw's "margin".
namespace margin {
inline constexpr char kParameter[] = "parameter"; // string
inline constexpr char kScale[] = "scale";         // number
inline constexpr char kAdd[] = "add";             // number
} // namespace margin

// A key's JSON type. Integer: a non-negative integer; Number: any number; Map: an object whose
// keys are names (axes, parameters, resources, languages), not keys of the schema.
enum class JsonType { String, Integer, Number, Boolean, Array, Object, Map };

// Who reads a key (a bitmask): a program reads a key when, without it (at one of its places), the
// program refuses the manifest or reads it differently. A key no program reads is there for
// people: the table says so in a comment with what it tells.
inline constexpr unsigned kNobody = 0;
// The runtime's reader: ShaderBuild::open (runtime/src/shader_build.cpp, manifest_reader.cpp,
// build_pass.cpp's read_passes).
inline constexpr unsigned kRuntime = 1u << 0;
// watergen merge of shards (generator/pipeline/shards) and the file lists it checks
// (generator/pipeline/manifest/manifest_files.cpp's named_files): the keys it looks up (it also
// holds the shards' heads, everything above "shaders" and "variants", to one text).
inline constexpr unsigned kMerge = 1u << 1;
// The build's C++ header (generator/pipeline/record/shaders_header.cpp); the uniform blocks and
// specialization constants it reads from the variants' variant.json, not from the manifest.
inline constexpr unsigned kHeader = 1u << 2;
// The generator's checks of an output directory and of the build record: whether a document is
// a manifest (generator/pipeline/output/output_target.cpp) and the files it names
// (manifest_files.cpp's manifest_named_files, for generator/pipeline/record).
inline constexpr unsigned kOutput = 1u << 3;

// One key path: the keys from the document down, "/"-separated; "*" for any element of an
// array and for any member of a Map.
struct ManifestKey {
    std::string_view path;
    JsonType type;
    unsigned readers;
};

// Every key path the writer can write, objects before their members, about in the order it writes
// them.
inline constexpr ManifestKey kManifestKeys[] = {
    // The document.
    {"/generator", JsonType::String, kRuntime | kOutput},
    // "material": the material built.
    {"/material", JsonType::Object, kRuntime | kHeader},
    {"/material/name", JsonType::String, kHeader},
    // For people: the material as its file states it (docs/user-guide.md "Material files"); each
    // variant carries what its shader takes of it.
    {"/material/description", JsonType::String, kNobody},
    {"/material/preset", JsonType::String, kNobody},
    {"/material/axes", JsonType::Map, kRuntime},
    {"/material/axes/*", JsonType::Array, kRuntime},
    {"/material/axes/*/*", JsonType::String, kRuntime},
    // For people: the material as its file states it (docs/user-guide.md "Material files"); each
    // variant carries what its shader takes of it.
    {"/material/rules", JsonType::Array, kNobody},
    {"/material/rules/*", JsonType::Object, kNobody},
    {"/material/rules/*/if", JsonType::String, kNobody},
    {"/material/rules/*/requires", JsonType::Map, kNobody},
    {"/material/rules/*/requires/*", JsonType::Array, kNobody},
    {"/material/rules/*/requires/*/*", JsonType::String, kNobody},
    {"/material/rules/*/excludes", JsonType::Map, kNobody},
    {"/material/rules/*/excludes/*", JsonType::Array, kNobody},
    {"/material/rules/*/excludes/*/*", JsonType::String, kNobody},
    {"/material/rules/*/why", JsonType::String, kNobody},
    {"/material/parameters", JsonType::Map, kNobody},
    {"/material/parameters/*", JsonType::Object, kNobody},
    {"/material/parameters/*/value", JsonType::Array, kNobody},
    {"/material/parameters/*/value/*", JsonType::Number, kNobody},
    {"/material/parameters/*/min", JsonType::Number, kNobody},
    {"/material/parameters/*/max", JsonType::Number, kNobody},
    {"/material/targets", JsonType::Array, kNobody},
    {"/material/targets/*", JsonType::String, kNobody},
    // "space": how many variants the full space and the material's space hold.
    // For people: how far the material and the scenes cut the space.
    {"/space", JsonType::Object, kNobody},
    {"/space/full", JsonType::Integer, kNobody},
    {"/space/material", JsonType::Integer, kNobody},
    // "scenes": one per scene built (or "unpruned"), in the build's order.
    {"/scenes", JsonType::Array, kRuntime | kMerge},
    {"/scenes/*", JsonType::Object, kRuntime | kMerge},
    {"/scenes/*/name", JsonType::String, kRuntime | kMerge},
    // For people: how the scene was planned: its file, its facts (the scene file's keys, spelled by
    // generator/plan/scene_file.cpp's scene_keys()), what it fixed, skipped and targets (`watergen
    // explain` tells the same).
    {"/scenes/*/pruned", JsonType::Boolean, kNobody},
    {"/scenes/*/description", JsonType::String, kNobody},
    {"/scenes/*/file", JsonType::String, kNobody},
    {"/scenes/*/facts", JsonType::Object, kNobody},
    {"/scenes/*/facts/shoreline", JsonType::Boolean, kNobody},
    {"/scenes/*/facts/water_depth", JsonType::Array, kNobody},
    {"/scenes/*/facts/water_depth/*", JsonType::Number, kNobody},
    {"/scenes/*/facts/camera_height", JsonType::Array, kNobody},
    {"/scenes/*/facts/camera_height/*", JsonType::Number, kNobody},
    {"/scenes/*/facts/camera_pitch", JsonType::Array, kNobody},
    {"/scenes/*/facts/camera_pitch/*", JsonType::Number, kNobody},
    {"/scenes/*/facts/sun_elevation", JsonType::Array, kNobody},
    {"/scenes/*/facts/sun_elevation/*", JsonType::Number, kNobody},
    {"/scenes/*/facts/reflection_sources", JsonType::Array, kNobody},
    {"/scenes/*/facts/reflection_sources/*", JsonType::String, kNobody},
    {"/scenes/*/facts/waves", JsonType::String, kNobody},
    {"/scenes/*/facts/precision", JsonType::String, kNobody},
    {"/scenes/*/facts/platforms", JsonType::Array, kNobody},
    {"/scenes/*/facts/platforms/*", JsonType::String, kNobody},
    {"/scenes/*/facts/scene_input", JsonType::String, kNobody},
    {"/scenes/*/variants", JsonType::Integer, kMerge},
    // For people: how the scene was planned: its file, its facts (the scene file's keys, spelled by
    // generator/plan/scene_file.cpp's scene_keys()), what it fixed, skipped and targets (`watergen
    // explain` tells the same).
    {"/scenes/*/skipped", JsonType::Integer, kNobody},
    {"/scenes/*/fixed", JsonType::Map, kNobody},
    {"/scenes/*/fixed/*", JsonType::Array, kNobody},
    {"/scenes/*/fixed/*/*", JsonType::Number, kNobody},
    {"/scenes/*/targets", JsonType::Array, kNobody},
    {"/scenes/*/targets/*", JsonType::String, kNobody},
    // "bindings": the binding map every shader of the build was emitted with (its resources as
    // generator/plan/binding_map_file.cpp writes a map file's).
    {"/bindings", JsonType::Object, kRuntime | kHeader},
    {"/bindings/map", JsonType::String, kRuntime | kHeader},
    {"/bindings/resources", JsonType::Map, kRuntime | kHeader},
    {"/bindings/resources/*", JsonType::Object, kRuntime | kHeader},
    {"/bindings/resources/*/kind", JsonType::String, kRuntime | kHeader},
    {"/bindings/resources/*/set", JsonType::Integer, kRuntime | kHeader},
    {"/bindings/resources/*/binding", JsonType::Integer, kRuntime | kHeader},
    {"/bindings/resources/*/hlsl_register", JsonType::Integer, kRuntime | kHeader},
    {"/bindings/resources/*/hlsl_space", JsonType::Integer, kRuntime | kHeader},
    {"/bindings/resources/*/msl", JsonType::Integer, kRuntime | kHeader},
    {"/bindings/resources/*/gl", JsonType::Integer, kRuntime | kHeader},
    {"/bindings/push_constant_bytes", JsonType::Integer, kRuntime | kHeader},
    // Specialized and branching builds only: "mode", then "shaders", the switched shaders built.
    {"/mode", JsonType::String, kRuntime | kMerge | kHeader},
    {"/shaders", JsonType::Array, kRuntime | kMerge | kHeader | kOutput},
    {"/shaders/*", JsonType::Object, kRuntime | kMerge | kHeader | kOutput},
    {"/shaders/*/scene", JsonType::String, kMerge},
    {"/shaders/*/key", JsonType::String, kMerge},
    // For people: the build cache's key of the entry's files (entries of one key share their
    // bytes).
    {"/shaders/*/content_hash", JsonType::String, kNobody},
    // For people: what the shader switches: the choices it offers per axis, its selectors and where
    // they are placed, how many variants it draws (each variant's entry places its own values).
    {"/shaders/*/axes", JsonType::Map, kNobody},
    {"/shaders/*/axes/*", JsonType::Array, kNobody},
    {"/shaders/*/axes/*/*", JsonType::String, kNobody},
    {"/shaders/*/same_as", JsonType::String, kMerge},
    {"/shaders/*/directory", JsonType::String, kRuntime | kMerge | kHeader | kOutput},
    {"/shaders/*/files", JsonType::Object, kRuntime | kMerge | kHeader | kOutput},
    {"/shaders/*/files/description", JsonType::Array, kRuntime | kMerge | kHeader | kOutput},
    {"/shaders/*/files/description/*", JsonType::String, kRuntime | kMerge | kHeader | kOutput},
    {"/shaders/*/files/glsl", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/shaders/*/files/glsl/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/shaders/*/files/hlsl", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/shaders/*/files/hlsl/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/shaders/*/files/spirv", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/shaders/*/files/spirv/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/shaders/*/files/glsl330", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/shaders/*/files/glsl330/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/shaders/*/files/essl300", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/shaders/*/files/essl300/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/shaders/*/files/msl", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/shaders/*/files/msl/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/shaders/*/files/reflection", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/shaders/*/files/reflection/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/shaders/*/reflection", JsonType::Object, kRuntime | kMerge},
    {"/shaders/*/reflection/uniform_block", JsonType::Object, kRuntime},
    {"/shaders/*/reflection/uniform_block/name", JsonType::String, kRuntime},
    // For people: where the block is bound and how large it is: an engine binds it where "bindings"
    // says and takes its size from the stage's reflection (*.reflect.json).
    {"/shaders/*/reflection/uniform_block/set", JsonType::Integer, kNobody},
    {"/shaders/*/reflection/uniform_block/binding", JsonType::Integer, kNobody},
    {"/shaders/*/reflection/uniform_block/push_constant", JsonType::Boolean, kNobody},
    {"/shaders/*/reflection/uniform_block/size", JsonType::Integer, kNobody},
    {"/shaders/*/reflection/uniform_block/members", JsonType::Array, kRuntime},
    {"/shaders/*/reflection/uniform_block/members/*", JsonType::Object, kRuntime},
    {"/shaders/*/reflection/uniform_block/members/*/name", JsonType::String, kRuntime},
    {"/shaders/*/reflection/uniform_block/members/*/type", JsonType::String, kRuntime},
    {"/shaders/*/reflection/uniform_block/members/*/offset", JsonType::Integer, kRuntime},
    {"/shaders/*/reflection/uniform_block/members/*/default", JsonType::Array, kRuntime},
    {"/shaders/*/reflection/uniform_block/members/*/default/*", JsonType::Number, kRuntime},
    {"/shaders/*/reflection/uniform_block/members/*/min", JsonType::Number, kRuntime},
    {"/shaders/*/reflection/uniform_block/members/*/max", JsonType::Number, kRuntime},
    // For people: a parameter's unit, where it comes from (the seed's section, its node) and its
    // array stride (always 16: std140 and cbuffer registers).
    {"/shaders/*/reflection/uniform_block/members/*/unit", JsonType::String, kNobody},
    {"/shaders/*/reflection/uniform_block/members/*/seed", JsonType::String, kNobody},
    {"/shaders/*/reflection/uniform_block/members/*/node", JsonType::String, kNobody},
    {"/shaders/*/reflection/uniform_block/members/*/array_size", JsonType::Integer, kRuntime},
    {"/shaders/*/reflection/uniform_block/members/*/host", JsonType::Object, kRuntime},
    {"/shaders/*/reflection/uniform_block/members/*/host/rule", JsonType::String, kRuntime},
    {"/shaders/*/reflection/uniform_block/members/*/host/inputs", JsonType::Array, kRuntime},
    {"/shaders/*/reflection/uniform_block/members/*/host/inputs/*", JsonType::String, kRuntime},
    // For people: a parameter's unit, where it comes from (the seed's section, its node) and its
    // array stride (always 16: std140 and cbuffer registers).
    {"/shaders/*/reflection/uniform_block/members/*/array_stride", JsonType::Integer, kNobody},
    // For people: the sampler's slot, which "bindings" gives too.
    {"/shaders/*/reflection/sampler", JsonType::Object, kNobody},
    {"/shaders/*/reflection/sampler/name", JsonType::String, kNobody},
    {"/shaders/*/reflection/sampler/set", JsonType::Integer, kNobody},
    {"/shaders/*/reflection/sampler/binding", JsonType::Integer, kNobody},
    {"/shaders/*/reflection/textures", JsonType::Array, kRuntime},
    {"/shaders/*/reflection/textures/*", JsonType::Object, kRuntime},
    {"/shaders/*/reflection/textures/*/name", JsonType::String, kRuntime},
    // For people: the texture's set, which "bindings" gives too.
    {"/shaders/*/reflection/textures/*/set", JsonType::Integer, kNobody},
    {"/shaders/*/reflection/textures/*/binding", JsonType::Integer, kRuntime},
    {"/shaders/*/reflection/textures/*/type", JsonType::String, kRuntime},
    // For people: the shader's specialization constants, their ids and ranges (the runtime places a
    // served variant's values by the ids its own "specialization_constants" give).
    {"/shaders/*/reflection/specialization_constants", JsonType::Array, kNobody},
    {"/shaders/*/reflection/specialization_constants/*", JsonType::Object, kNobody},
    {"/shaders/*/reflection/specialization_constants/*/name", JsonType::String, kNobody},
    {"/shaders/*/reflection/specialization_constants/*/type", JsonType::String, kNobody},
    {"/shaders/*/reflection/specialization_constants/*/constant_ids", JsonType::Array, kNobody},
    {"/shaders/*/reflection/specialization_constants/*/constant_ids/*", JsonType::Integer, kNobody},
    {"/shaders/*/reflection/specialization_constants/*/default", JsonType::Array, kNobody},
    {"/shaders/*/reflection/specialization_constants/*/default/*", JsonType::Number, kNobody},
    {"/shaders/*/reflection/specialization_constants/*/min", JsonType::Number, kNobody},
    {"/shaders/*/reflection/specialization_constants/*/max", JsonType::Number, kNobody},
    {"/shaders/*/reflection/specialization_constants/*/unit", JsonType::String, kNobody},
    {"/shaders/*/reflection/specialization_constants/*/seed", JsonType::String, kNobody},
    {"/shaders/*/reflection/specialization_constants/*/node", JsonType::String, kNobody},
    {"/shaders/*/reflection/specialization_constants/*/array_size", JsonType::Integer, kNobody},
    {"/shaders/*/reflection/specialization_constants/*/array_stride", JsonType::Integer, kNobody},
    {"/shaders/*/spirv_instructions", JsonType::Map, kMerge},
    // For people: SPIR-V instruction counts per language and stage, to compare variants by.
    {"/shaders/*/spirv_instructions/*", JsonType::Object, kNobody},
    {"/shaders/*/spirv_instructions/*/fragment", JsonType::Integer, kNobody},
    {"/shaders/*/spirv_instructions/*/fragment_optimized", JsonType::Integer, kNobody},
    {"/shaders/*/spirv_instructions/*/vertex", JsonType::Integer, kNobody},
    {"/shaders/*/spirv_instructions/*/tess_control", JsonType::Integer, kNobody},
    {"/shaders/*/spirv_instructions/*/tess_evaluation", JsonType::Integer, kNobody},
    // For people: the shader's mesh: the runtime checks it, refusing one without the keys it
    // requires, but gives it to none of the variants the shader draws
    // (runtime/src/shader_build.cpp's read_served copies no geometry).
    {"/shaders/*/geometry", JsonType::Object, kNobody},
    {"/shaders/*/geometry/name", JsonType::String, kRuntime},
    {"/shaders/*/geometry/stages", JsonType::Array, kRuntime},
    // For people: the shader's mesh: the runtime checks it, refusing one without the keys it
    // requires, but gives it to none of the variants the shader draws
    // (runtime/src/shader_build.cpp's read_served copies no geometry).
    {"/shaders/*/geometry/stages/*", JsonType::String, kNobody},
    {"/shaders/*/geometry/topology", JsonType::String, kNobody},
    {"/shaders/*/geometry/vertex_stride", JsonType::Integer, kRuntime},
    {"/shaders/*/geometry/vertex_inputs", JsonType::Array, kRuntime},
    {"/shaders/*/geometry/vertex_inputs/*", JsonType::Object, kRuntime},
    {"/shaders/*/geometry/vertex_inputs/*/name", JsonType::String, kRuntime},
    {"/shaders/*/geometry/vertex_inputs/*/location", JsonType::Integer, kRuntime},
    {"/shaders/*/geometry/vertex_inputs/*/floats", JsonType::Integer, kRuntime},
    {"/shaders/*/geometry/vertex_inputs/*/offset", JsonType::Integer, kRuntime},
    // For people: how the mesh is made and drawn (the shader's variants do not carry it).
    {"/shaders/*/geometry/grid", JsonType::Object, kNobody},
    {"/shaders/*/geometry/grid/kind", JsonType::String, kNobody},
    {"/shaders/*/geometry/grid/made_by", JsonType::String, kNobody},
    {"/shaders/*/geometry/grid/parameters", JsonType::Array, kNobody},
    {"/shaders/*/geometry/grid/parameters/*", JsonType::String, kNobody},
    {"/shaders/*/geometry/front_face", JsonType::String, kNobody},
    {"/shaders/*/geometry/patch_control_points", JsonType::Integer, kNobody},
    {"/shaders/*/geometry/tessellation", JsonType::Object, kNobody},
    {"/shaders/*/geometry/tessellation/max_factor", JsonType::Number, kNobody},
    {"/shaders/*/geometry/tessellation/parameters", JsonType::Array, kNobody},
    {"/shaders/*/geometry/tessellation/parameters/*", JsonType::String, kNobody},
    // For people: what the shader switches: the choices it offers per axis, its selectors and where
    // they are placed, how many variants it draws (each variant's entry places its own values).
    {"/shaders/*/selectors", JsonType::Array, kNobody},
    {"/shaders/*/selectors/*", JsonType::Object, kNobody},
    {"/shaders/*/selectors/*/axis", JsonType::String, kNobody},
    {"/shaders/*/selectors/*/parameter", JsonType::String, kNobody},
    {"/shaders/*/selectors/*/choices", JsonType::Array, kNobody},
    {"/shaders/*/selectors/*/choices/*", JsonType::String, kNobody},
    {"/shaders/*/selectors/*/constant_id", JsonType::Integer, kNobody},
    {"/shaders/*/selectors/*/offset", JsonType::Integer, kNobody},
    {"/shaders/*/variants", JsonType::Integer, kNobody},
    {"/shaders/*/folded_parameters", JsonType::Map, kRuntime},
    {"/shaders/*/folded_parameters/*", JsonType::Array, kRuntime},
    {"/shaders/*/folded_parameters/*/*", JsonType::Number, kRuntime},
    {"/shaders/*/removed_parameters", JsonType::Array, kRuntime},
    {"/shaders/*/removed_parameters/*", JsonType::Object, kRuntime},
    {"/shaders/*/removed_parameters/*/name", JsonType::String, kRuntime},
    // For people: what folding removed and why (the scene's facts as text), and the live IR nodes
    // before and after.
    {"/shaders/*/removed_parameters/*/because", JsonType::Array, kNobody},
    {"/shaders/*/removed_parameters/*/because/*", JsonType::String, kNobody},
    {"/shaders/*/removed_textures", JsonType::Array, kNobody},
    {"/shaders/*/removed_textures/*", JsonType::Object, kNobody},
    {"/shaders/*/removed_textures/*/name", JsonType::String, kNobody},
    {"/shaders/*/removed_textures/*/because", JsonType::Array, kNobody},
    {"/shaders/*/removed_textures/*/because/*", JsonType::String, kNobody},
    {"/shaders/*/removed_terms", JsonType::Array, kNobody},
    {"/shaders/*/removed_terms/*", JsonType::Object, kNobody},
    {"/shaders/*/removed_terms/*/node", JsonType::String, kNobody},
    {"/shaders/*/removed_terms/*/term", JsonType::String, kNobody},
    {"/shaders/*/removed_terms/*/because", JsonType::Array, kNobody},
    {"/shaders/*/removed_terms/*/because/*", JsonType::String, kNobody},
    {"/shaders/*/live_ir_nodes", JsonType::Object, kNobody},
    {"/shaders/*/live_ir_nodes/before", JsonType::Integer, kNobody},
    {"/shaders/*/live_ir_nodes/after", JsonType::Integer, kNobody},
    // "variants": every variant, sorted by scene and key. A permutations build's entry is built
    // (its files, reflection, fold); a specialized or branching build's names the shader that draws
    // it and its selector values, placed.
    {"/variants", JsonType::Array, kRuntime | kMerge | kHeader | kOutput},
    {"/variants/*", JsonType::Object, kRuntime | kMerge | kHeader | kOutput},
    {"/variants/*/scene", JsonType::String, kRuntime | kMerge | kHeader},
    {"/variants/*/key", JsonType::String, kRuntime | kMerge | kHeader},
    {"/variants/*/hash", JsonType::String, kRuntime | kHeader},
    // For people: the build cache's key of the entry's files (entries of one key share their
    // bytes).
    {"/variants/*/content_hash", JsonType::String, kNobody},
    {"/variants/*/shader", JsonType::String, kRuntime | kMerge | kHeader | kOutput},
    {"/variants/*/nodes", JsonType::Map, kRuntime},
    {"/variants/*/nodes/*", JsonType::String, kRuntime},
    {"/variants/*/folded_parameters", JsonType::Map, kRuntime},
    {"/variants/*/folded_parameters/*", JsonType::Array, kRuntime},
    {"/variants/*/folded_parameters/*/*", JsonType::Number, kRuntime},
    {"/variants/*/removed_parameters", JsonType::Array, kRuntime},
    {"/variants/*/removed_parameters/*", JsonType::Object, kRuntime},
    {"/variants/*/removed_parameters/*/name", JsonType::String, kRuntime},
    // For people: what folding removed and why (the scene's facts as text), and the live IR nodes
    // before and after.
    {"/variants/*/removed_parameters/*/because", JsonType::Array, kNobody},
    {"/variants/*/removed_parameters/*/because/*", JsonType::String, kNobody},
    {"/variants/*/removed_textures", JsonType::Array, kNobody},
    {"/variants/*/removed_textures/*", JsonType::Object, kNobody},
    {"/variants/*/removed_textures/*/name", JsonType::String, kNobody},
    {"/variants/*/removed_textures/*/because", JsonType::Array, kNobody},
    {"/variants/*/removed_textures/*/because/*", JsonType::String, kNobody},
    {"/variants/*/removed_terms", JsonType::Array, kNobody},
    {"/variants/*/removed_terms/*", JsonType::Object, kNobody},
    {"/variants/*/removed_terms/*/node", JsonType::String, kNobody},
    {"/variants/*/removed_terms/*/term", JsonType::String, kNobody},
    {"/variants/*/removed_terms/*/because", JsonType::Array, kNobody},
    {"/variants/*/removed_terms/*/because/*", JsonType::String, kNobody},
    {"/variants/*/live_ir_nodes", JsonType::Object, kNobody},
    {"/variants/*/live_ir_nodes/before", JsonType::Integer, kNobody},
    {"/variants/*/live_ir_nodes/after", JsonType::Integer, kNobody},
    {"/variants/*/same_as", JsonType::String, kMerge},
    {"/variants/*/directory", JsonType::String, kRuntime | kMerge | kOutput},
    {"/variants/*/files", JsonType::Object, kRuntime | kMerge | kHeader | kOutput},
    {"/variants/*/files/description", JsonType::Array, kRuntime | kMerge | kHeader | kOutput},
    {"/variants/*/files/description/*", JsonType::String, kRuntime | kMerge | kHeader | kOutput},
    {"/variants/*/files/glsl", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/variants/*/files/glsl/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/variants/*/files/hlsl", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/variants/*/files/hlsl/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/variants/*/files/spirv", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/variants/*/files/spirv/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/variants/*/files/glsl330", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/variants/*/files/glsl330/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/variants/*/files/essl300", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/variants/*/files/essl300/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/variants/*/files/msl", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/variants/*/files/msl/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/variants/*/files/reflection", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/variants/*/files/reflection/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/variants/*/reflection", JsonType::Object, kRuntime | kMerge},
    {"/variants/*/reflection/uniform_block", JsonType::Object, kRuntime},
    {"/variants/*/reflection/uniform_block/name", JsonType::String, kRuntime},
    // For people: where the block is bound and how large it is: an engine binds it where "bindings"
    // says and takes its size from the stage's reflection (*.reflect.json).
    {"/variants/*/reflection/uniform_block/set", JsonType::Integer, kNobody},
    {"/variants/*/reflection/uniform_block/binding", JsonType::Integer, kNobody},
    {"/variants/*/reflection/uniform_block/push_constant", JsonType::Boolean, kNobody},
    {"/variants/*/reflection/uniform_block/size", JsonType::Integer, kNobody},
    {"/variants/*/reflection/uniform_block/members", JsonType::Array, kRuntime},
    {"/variants/*/reflection/uniform_block/members/*", JsonType::Object, kRuntime},
    {"/variants/*/reflection/uniform_block/members/*/name", JsonType::String, kRuntime},
    {"/variants/*/reflection/uniform_block/members/*/type", JsonType::String, kRuntime},
    {"/variants/*/reflection/uniform_block/members/*/offset", JsonType::Integer, kRuntime},
    {"/variants/*/reflection/uniform_block/members/*/default", JsonType::Array, kRuntime},
    {"/variants/*/reflection/uniform_block/members/*/default/*", JsonType::Number, kRuntime},
    {"/variants/*/reflection/uniform_block/members/*/min", JsonType::Number, kRuntime},
    {"/variants/*/reflection/uniform_block/members/*/max", JsonType::Number, kRuntime},
    // For people: a parameter's unit, where it comes from (the seed's section, its node) and its
    // array stride (always 16: std140 and cbuffer registers).
    {"/variants/*/reflection/uniform_block/members/*/unit", JsonType::String, kNobody},
    {"/variants/*/reflection/uniform_block/members/*/seed", JsonType::String, kNobody},
    {"/variants/*/reflection/uniform_block/members/*/node", JsonType::String, kNobody},
    {"/variants/*/reflection/uniform_block/members/*/array_size", JsonType::Integer, kRuntime},
    {"/variants/*/reflection/uniform_block/members/*/host", JsonType::Object, kRuntime},
    {"/variants/*/reflection/uniform_block/members/*/host/rule", JsonType::String, kRuntime},
    {"/variants/*/reflection/uniform_block/members/*/host/inputs", JsonType::Array, kRuntime},
    {"/variants/*/reflection/uniform_block/members/*/host/inputs/*", JsonType::String, kRuntime},
    // For people: a parameter's unit, where it comes from (the seed's section, its node) and its
    // array stride (always 16: std140 and cbuffer registers).
    {"/variants/*/reflection/uniform_block/members/*/array_stride", JsonType::Integer, kNobody},
    // For people: the sampler's slot, which "bindings" gives too.
    {"/variants/*/reflection/sampler", JsonType::Object, kNobody},
    {"/variants/*/reflection/sampler/name", JsonType::String, kNobody},
    {"/variants/*/reflection/sampler/set", JsonType::Integer, kNobody},
    {"/variants/*/reflection/sampler/binding", JsonType::Integer, kNobody},
    {"/variants/*/reflection/textures", JsonType::Array, kRuntime},
    {"/variants/*/reflection/textures/*", JsonType::Object, kRuntime},
    {"/variants/*/reflection/textures/*/name", JsonType::String, kRuntime},
    // For people: the texture's set, which "bindings" gives too.
    {"/variants/*/reflection/textures/*/set", JsonType::Integer, kNobody},
    {"/variants/*/reflection/textures/*/binding", JsonType::Integer, kRuntime},
    {"/variants/*/reflection/textures/*/type", JsonType::String, kRuntime},
    // For people: the shader's specialization constants, their ids and ranges (the runtime places a
    // served variant's values by the ids its own "specialization_constants" give).
    {"/variants/*/reflection/specialization_constants", JsonType::Array, kNobody},
    {"/variants/*/reflection/specialization_constants/*", JsonType::Object, kNobody},
    {"/variants/*/reflection/specialization_constants/*/name", JsonType::String, kNobody},
    {"/variants/*/reflection/specialization_constants/*/type", JsonType::String, kNobody},
    {"/variants/*/reflection/specialization_constants/*/constant_ids", JsonType::Array, kNobody},
    {"/variants/*/reflection/specialization_constants/*/constant_ids/*", JsonType::Integer,
     kNobody},
    {"/variants/*/reflection/specialization_constants/*/default", JsonType::Array, kNobody},
    {"/variants/*/reflection/specialization_constants/*/default/*", JsonType::Number, kNobody},
    {"/variants/*/reflection/specialization_constants/*/min", JsonType::Number, kNobody},
    {"/variants/*/reflection/specialization_constants/*/max", JsonType::Number, kNobody},
    {"/variants/*/reflection/specialization_constants/*/unit", JsonType::String, kNobody},
    {"/variants/*/reflection/specialization_constants/*/seed", JsonType::String, kNobody},
    {"/variants/*/reflection/specialization_constants/*/node", JsonType::String, kNobody},
    {"/variants/*/reflection/specialization_constants/*/array_size", JsonType::Integer, kNobody},
    {"/variants/*/reflection/specialization_constants/*/array_stride", JsonType::Integer, kNobody},
    {"/variants/*/spirv_instructions", JsonType::Map, kMerge},
    // For people: SPIR-V instruction counts per language and stage, to compare variants by.
    {"/variants/*/spirv_instructions/*", JsonType::Object, kNobody},
    {"/variants/*/spirv_instructions/*/fragment", JsonType::Integer, kNobody},
    {"/variants/*/spirv_instructions/*/fragment_optimized", JsonType::Integer, kNobody},
    {"/variants/*/spirv_instructions/*/vertex", JsonType::Integer, kNobody},
    {"/variants/*/spirv_instructions/*/tess_control", JsonType::Integer, kNobody},
    {"/variants/*/spirv_instructions/*/tess_evaluation", JsonType::Integer, kNobody},
    {"/variants/*/geometry", JsonType::Object, kRuntime},
    {"/variants/*/geometry/name", JsonType::String, kRuntime},
    {"/variants/*/geometry/stages", JsonType::Array, kRuntime},
    {"/variants/*/geometry/stages/*", JsonType::String, kRuntime},
    // For people: how the mesh is made and drawn, which water_grid() and the variant pipeline fix
    // (runtime/water_grid.h).
    {"/variants/*/geometry/topology", JsonType::String, kNobody},
    {"/variants/*/geometry/vertex_stride", JsonType::Integer, kRuntime},
    {"/variants/*/geometry/vertex_inputs", JsonType::Array, kRuntime},
    {"/variants/*/geometry/vertex_inputs/*", JsonType::Object, kRuntime},
    {"/variants/*/geometry/vertex_inputs/*/name", JsonType::String, kRuntime},
    {"/variants/*/geometry/vertex_inputs/*/location", JsonType::Integer, kRuntime},
    {"/variants/*/geometry/vertex_inputs/*/floats", JsonType::Integer, kRuntime},
    {"/variants/*/geometry/vertex_inputs/*/offset", JsonType::Integer, kRuntime},
    // For people: how the mesh is made and drawn, which water_grid() and the variant pipeline fix
    // (runtime/water_grid.h).
    {"/variants/*/geometry/grid", JsonType::Object, kNobody},
    {"/variants/*/geometry/grid/kind", JsonType::String, kNobody},
    {"/variants/*/geometry/grid/made_by", JsonType::String, kNobody},
    {"/variants/*/geometry/grid/parameters", JsonType::Array, kNobody},
    {"/variants/*/geometry/grid/parameters/*", JsonType::String, kNobody},
    {"/variants/*/geometry/front_face", JsonType::String, kNobody},
    {"/variants/*/geometry/patch_control_points", JsonType::Integer, kRuntime},
    // For people: how the mesh is made and drawn, which water_grid() and the variant pipeline fix
    // (runtime/water_grid.h).
    {"/variants/*/geometry/tessellation", JsonType::Object, kNobody},
    {"/variants/*/geometry/tessellation/max_factor", JsonType::Number, kNobody},
    {"/variants/*/geometry/tessellation/parameters", JsonType::Array, kNobody},
    {"/variants/*/geometry/tessellation/parameters/*", JsonType::String, kNobody},
    // For people: the variant's selector values by parameter ("specialization_constants" or
    // "uniforms" place them; the runtime reads those) and the names and offsets beside the places
    // it uses.
    {"/variants/*/selectors", JsonType::Map, kNobody},
    {"/variants/*/selectors/*", JsonType::Number, kNobody},
    {"/variants/*/specialization_constants", JsonType::Array, kRuntime},
    {"/variants/*/specialization_constants/*", JsonType::Object, kRuntime},
    {"/variants/*/specialization_constants/*/id", JsonType::Integer, kRuntime},
    // For people: the variant's selector values by parameter ("specialization_constants" or
    // "uniforms" place them; the runtime reads those) and the names and offsets beside the places
    // it uses.
    {"/variants/*/specialization_constants/*/name", JsonType::String, kNobody},
    {"/variants/*/specialization_constants/*/value", JsonType::Number, kRuntime},
    {"/variants/*/uniforms", JsonType::Array, kRuntime},
    {"/variants/*/uniforms/*", JsonType::Object, kRuntime},
    {"/variants/*/uniforms/*/name", JsonType::String, kRuntime},
    // For people: the variant's selector values by parameter ("specialization_constants" or
    // "uniforms" place them; the runtime reads those) and the names and offsets beside the places
    // it uses.
    {"/variants/*/uniforms/*/offset", JsonType::Integer, kNobody},
    {"/variants/*/uniforms/*/value", JsonType::Number, kRuntime},
    {"/variants/*/frozen", JsonType::Map, kRuntime | kMerge | kOutput},
    {"/variants/*/frozen/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/variants/*/passes", JsonType::Object, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics", JsonType::Object, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/method", JsonType::String, kRuntime},
    {"/variants/*/passes/caustics/wave_model", JsonType::String, kRuntime},
    {"/variants/*/passes/caustics/directory", JsonType::String, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/files", JsonType::Object, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/files/description", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/files/description/*", JsonType::String,
     kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/files/glsl", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/files/glsl/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/files/hlsl", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/files/hlsl/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/files/spirv", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/files/spirv/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/files/glsl330", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/files/glsl330/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/files/essl300", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/files/essl300/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/files/msl", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/files/msl/*", JsonType::String, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/files/reflection", JsonType::Array, kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/files/reflection/*", JsonType::String,
     kRuntime | kMerge | kOutput},
    {"/variants/*/passes/caustics/draw", JsonType::Object, kRuntime},
    {"/variants/*/passes/caustics/draw/primitive", JsonType::String, kRuntime},
    {"/variants/*/passes/caustics/draw/attribute", JsonType::String, kRuntime},
    {"/variants/*/passes/caustics/draw/cells_per_texel", JsonType::Integer, kRuntime},
    {"/variants/*/passes/caustics/draw/margin", JsonType::Object, kRuntime},
    {"/variants/*/passes/caustics/draw/margin/parameter", JsonType::String, kRuntime},
    {"/variants/*/passes/caustics/draw/margin/scale", JsonType::Number, kRuntime},
    {"/variants/*/passes/caustics/draw/margin/add", JsonType::Number, kRuntime},
    {"/variants/*/passes/caustics/draw/window", JsonType::String, kRuntime},
    {"/variants/*/passes/caustics/draw/texels", JsonType::Integer, kRuntime},
    {"/variants/*/passes/caustics/draw/format", JsonType::String, kRuntime},
    {"/variants/*/passes/caustics/draw/channel", JsonType::String, kRuntime},
    {"/variants/*/passes/caustics/draw/clear", JsonType::Number, kRuntime},
    {"/variants/*/passes/caustics/draw/blend", JsonType::String, kRuntime},
    {"/variants/*/passes/caustics/draw/photon_share", JsonType::String, kRuntime},
    {"/variants/*/passes/caustics/values", JsonType::Map, kRuntime},
    {"/variants/*/passes/caustics/values/*", JsonType::Array, kRuntime},
    {"/variants/*/passes/caustics/values/*/*", JsonType::Number, kRuntime},
};

} // namespace watergen::manifest_schema
