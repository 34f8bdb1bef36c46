// One variant from description to validated artifacts: compose the graph, emit GLSL and HLSL,
// run each stage through the in-process toolchain, and map compiler errors back to nodes.
#pragma once

#include <array>
#include <initializer_list>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "watergen/ir/emit/emitter.h"
#include "watergen/pipeline/variant/stage_memo.h"
#include "watergen/toolchain/toolchain.h"
#include "watergen/water/water_shader.h"

namespace watergen {

struct StageBuild {
    EmittedShader source;
    ToolchainOutputs toolchain;
};

struct LanguageBuild {
    Language language = Language::Glsl;
    StageBuild vertex, fragment;
    // A tessellated geometry's patch stages (tessellation control, evaluation); without a
    // source file otherwise.
    StageBuild control, evaluation;
    bool tessellated() const { return !control.source.file_name.empty(); }
    std::vector<const StageBuild*> stages() const; // those present, in pipeline order
};

struct VariantBuild {
    WaterShader shader;
    std::array<LanguageBuild, 2> languages; // GLSL, HLSL
    Diagnostics diagnostics;                // every stage's, nodes filled in where known
    bool ok() const { return !has_errors(diagnostics); }
};

// How build_shader runs the toolchain. The default runs every stage of both languages through
// the whole chain. A build (run_build_jobs) ships SPIRV-Cross text of the GLSL path only (the
// HLSL path's module is the same program again), so it skips the HLSL path's cross-compiles,
// and finds stages compiled for another variant in its memo.
struct StageCompile {
    bool hlsl_cross_compile = true;
    StageMemo* memo = nullptr; // none: every stage compiled
};

// One emitted stage through the toolchain (`compile` says how far), its reflection checked
// against the slots it was emitted with; the diagnostics go to `all`, glslang's with the nodes
// of the lines they name. `key`: the variant whose stamp the source carries (the memo finds the
// stage without it).
StageBuild build_stage(EmittedShader source, Diagnostics& all, const StageCompile& compile = {},
                       const std::string& key = "", bool strict_half = false);

// The request build_shader compiles `stage` with (its Metal indices from the stage's binding
// slots), and how far its chain runs under `compile`.
CompileRequest stage_request(const EmittedShader& stage, bool strict_half = false);
CrossCompile stage_cross(Language language, const StageCompile& compile);
// `options` with the default binding map (the watergen profile) when it names none: every
// stage a build writes, renders or probes is emitted with a map.
EmitOptions with_bindings(EmitOptions options);
// The watergen profile with every texture of `graphs` it does not place appended in set 0 (after
// its last binding, in declaration order): what build_shader and the two-stage builds use when
// given no map, so a shader of a test's or a user's own nodes still builds.
BindingMap default_map_for(std::initializer_list<const Graph*> graphs);
// Where a stage's resources are bound in every target, as text for a content hash (the sources
// spell the Vulkan and HLSL places; the Metal indices are SPIRV-Cross's options, the GL units the
// manifest's).
std::string slots_text(const ShaderInterface& in);
// The stage's reflected descriptors against the slots it was emitted with: each at its set and
// binding, none missing, none extra (a probe's own buffers aside); errors naming the resource.
Diagnostics check_reflected_bindings(const Reflection& reflection, const EmittedShader& stage);

// Builds both languages of one variant. A graph with type errors stops before emission.
// `options.bindings` null: default_map_for(the fragment graph).
// Cost: two toolchain runs per stage (a few ms each); thread-safe.
// `options.strict_half` writes a half variant's relaxed math in explicit 16-bit types (see
// EmitOptions), for rendering at 16 bits on the GPU; builds written to disk use the default.
VariantBuild build_variant(const Variant& variant, const Preset* preset = nullptr,
                           const EmitOptions& options = {});
// Every stage of both languages of a composed shader, emitted (sources and interfaces, no
// toolchain): the fullscreen vertex stage and the fragment, or a mesh's stages
// (WaterShader::mesh) sharing one parameter block with the fragment, whose inputs are then
// mesh_fragment_inputs(). `options.bindings` must be set. Errors (the graphs' own first) to `ds`.
std::array<LanguageBuild, 2> emit_shader_stages(const WaterShader& shader,
                                                const EmitOptions& options, Diagnostics& ds);
// Same for an already composed shader (a custom description, or a test's ill-typed one).
VariantBuild build_shader(WaterShader shader, const EmitOptions& options = {},
                          const StageCompile& compile = {});

// The files a build writes, relative path -> contents, e.g. "glsl/water.frag.spv": sources,
// SPIR-V, reflection of both languages, SPIRV-Cross text of the GLSL path. Empty when the
// build failed.
std::map<std::string, std::string> variant_files(const VariantBuild& build);
// The names variant_files gives every successful build of a variant with (tessellated) or
// without patch stages, sorted.
std::vector<std::string> variant_file_names(bool tessellated = false);

// The uniform block of a stage's interface as variant.json lists it ("uniform_block": name,
// set, binding, size, members with their offsets, defaults, ranges and units).
nlohmann::ordered_json uniform_block_json(const ShaderInterface& in);
// Its parameters held in specialization constants (loop counts), with their constant ids.
nlohmann::ordered_json specialization_json(const ShaderInterface& in);

// Emits a vertex and a fragment graph in both languages (files <lang>/<stem>.<ext>, the
// vertex entry named `stage_name`, stamped with `key`) and runs each through the toolchain (a
// few ms each); stops at the first graph with errors. The mesh path and the caustics pass
// share it. `bindings`: null for the default map.
std::array<LanguageBuild, 2> build_two_stages(const Graph& vertex, const Graph& fragment,
                                              const std::string& stage_name,
                                              const std::string& stem, const std::string& key,
                                              Diagnostics& diagnostics,
                                              const BindingMap* bindings = nullptr);
// Its two halves, for a caller that looks its files up by the sources first: the emission
// (sources and interfaces only, no toolchain), then the toolchain over every emitted stage.
std::array<LanguageBuild, 2> emit_two_stages(const Graph& vertex, const Graph& fragment,
                                             const std::string& stage_name, const std::string& stem,
                                             const std::string& key, Diagnostics& diagnostics,
                                             const BindingMap* bindings = nullptr);
void compile_two_stages(std::array<LanguageBuild, 2>& languages, Diagnostics& diagnostics,
                        const StageCompile& compile = {});
// The names add_stage_files gives both languages' stages of `stem`, sorted; with the patch
// stages' when `tessellated`.
std::vector<std::string> stage_file_list(const std::string& stem, bool tessellated = false);
// The files of both languages of a build as variant_files writes them, under the names
// <lang>/<stem>.<stage>.<kind> (sources, SPIR-V plain and optimised, reflection, and for the
// GLSL path the cross-compiled texts stamped with `key`).
void add_stage_files(const std::array<LanguageBuild, 2>& languages, const std::string& stem,
                     const std::string& key, std::map<std::string, std::string>& files);

} // namespace watergen
