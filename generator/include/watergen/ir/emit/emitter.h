// Walks a Graph and writes shader source: GLSL 450 for Vulkan, or HLSL (SM 5 syntax, as
// glslang's HLSL front end reads it). Language differences live in the syntax classes
// (ir/glsl_syntax.cpp, ir/hlsl_syntax.cpp) and in the skeletons under templates/.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "watergen/ir/core/ir.h"
#include "watergen/ir/emit/binding_map.h"
#include "watergen/ir/emit/specialization.h"
#include "watergen/ir/emit/uniform_layout.h"
#include "watergen/runtime/reflection.h"

namespace watergen {

enum class Language { Glsl, Hlsl };
const char* to_string(Language l);
// "frag.glsl", "frag.hlsl", ..., "tesc.hlsl" (hull), "tese.hlsl" (domain).
const char* file_extension(Language l, ShaderStage s);

// The numbering of a shader emitted without a binding map (EmitOptions::bindings), in set 0:
// the block, the sampler, then the textures it reads in declaration order. A build always
// emits with a map (the watergen profile by default), which keeps every slot across variants.
constexpr uint32_t kParamsBinding = 0;       // uniform block "WaterParams"
constexpr uint32_t kSamplerBinding = 1;      // sampler "linear_clamp"
constexpr uint32_t kFirstTextureBinding = 2; // textures in declaration order

struct TextureBinding {
    std::string name;
    Type type = Type::Texture2D;
    uint32_t binding = 0;
    uint32_t set = 0;
};

struct ShaderInterface {
    UniformLayout uniforms; // empty when the shader reads no parameter from the block
    // Every parameter the shader reads, in declaration order; those marked `specialization`
    // are the specialization constants in `specialization`, the others are in `uniforms`.
    std::vector<Parameter> parameters;
    std::vector<SpecializationSlot> specialization; // ascending id
    std::vector<TextureBinding> textures;
    std::vector<std::pair<std::string, Type>> varyings; // fragment inputs, location = index
    // Where the block (when it has members), the sampler (when a texture is read) and each
    // texture are bound, in every target.
    std::vector<ResourceSlot> slots;
    const ResourceSlot* slot(const std::string& resource) const;
};

struct EmittedShader {
    Language language = Language::Glsl;
    ShaderStage stage = ShaderStage::Fragment;
    std::string file_name;
    std::string source;
    // Feature node that produced each line (index = line - 1); "" for skeleton lines.
    std::vector<std::string> line_origin;
    ShaderInterface interface;
};

// How relaxed-precision nodes are written. By default they are a precision hint (GLSL mediump,
// HLSL min16float) that desktop drivers, lavapipe included, run at 32 bits. strict_half writes
// them in explicit binary16 types instead (GLSL float16_t / f16vecN with
// GL_EXT_shader_explicit_arithmetic_types_float16, HLSL half / halfN, which need
// CompileRequest::hlsl_16bit_types), converting explicitly wherever 16- and 32-bit values meet
// (parameters, inputs, texture coordinates, the output): the GPU then computes what a mobile
// GPU computes for mediump, every operation rounded to binary16 (needs shaderFloat16).
//
// specialization_constants names parameters emitted as Vulkan specialization constants instead
// of uniform-block members (as if their Parameter::specialization were set): GLSL
// `layout(constant_id = N) const float`, HLSL `[[vk::constant_id(N)]] const float`, one per
// component of a vector, ids in declaration order (ir/specialization.h). A name no parameter of
// the graph declares is an error; one the shader does not read is ignored.
// Which unroll hint each loop is emitted with: its own (LoopOptions::unroll), or one for all
// (to compare kept loops with unrolled ones on the same shader).
enum class LoopUnroll { AsHinted, All, None };

struct EmitOptions {
    bool strict_half = false;
    std::set<std::string> specialization_constants =
        {}; // "= {}": EmitOptions{x} stays warning-free
    LoopUnroll unroll = LoopUnroll::AsHinted;
    // Where each resource is bound (binding_map.h); null: the dense numbering above. A
    // resource the shader reads that the map does not place is an error naming it.
    const BindingMap* bindings = nullptr;
    // The parameter block when the stages of a pipeline share one (shared_block_parameters,
    // tessellation_emitter.h): every member declared at its offset whatever this stage reads;
    // a parameter read that the block lacks is an error. Null: the parameters the graph reads.
    const std::vector<Parameter>* block = nullptr;
    // The stage inputs in location order, as the stage before writes them (a mesh's
    // mesh_fragment_inputs()): each declared, read or not; a Varying the graph reads that is
    // not among them is an error. Null: the Varyings the graph reads, in order.
    const std::vector<std::pair<std::string, Type>>* inputs = nullptr;
};

// "hinted", "all", "none" (the --unroll flag); nullopt for another word.
std::optional<LoopUnroll> parse_loop_unroll(const std::string& word);
const char* to_string(LoopUnroll unroll); // the word parse_loop_unroll takes
// The hint a loop with its own `hint` is written with under `unroll`.
UnrollHint emitted_hint(LoopUnroll unroll, UnrollHint hint);

// The stamp line every generated file carries.
std::string stamp_text(const std::string& variant_key);

// Emits the fragment stage of `g` (output "color"). Only live nodes are written, and only the
// parameters and textures they read are declared. Cost: linear in the live graph.
EmittedShader emit_fragment(const Graph& g, Language language, const std::string& file_name,
                            const std::string& variant_key, Diagnostics& diagnostics,
                            const EmitOptions& options = {});

// The loops emit_fragment writes for `g`, in the order of its text: each loop before the loops
// of its body, a switch's cases in order (each case's loops, though only one case runs). A
// driver compiles them in that order; it may unroll some away.
struct EmittedLoop {
    int trip_count = 0;                 // LoopBody::trip_count: the most iterations
    uint32_t depth = 0;                 // 0 outermost
    bool bounded_by_data = false;       // LoopBody::counted or has_exit: may run fewer
    UnrollHint hint = UnrollHint::Keep; // as written (EmitOptions::unroll over the loop's own)
};
std::vector<EmittedLoop> emitted_loops(const Graph& g, LoopUnroll unroll = LoopUnroll::AsHinted);

// The fullscreen-triangle vertex stage that feeds v_uv to the water pass.
EmittedShader emit_fullscreen_vertex(Language language, const std::string& file_name,
                                     const std::string& variant_key);

// The numeric harness: a compute shader that evaluates every output of `g` for a batch of
// input tuples. Each Varying of `g` (in creation order) is an input read from the storage buffer
// probe_in and each output is written to probe_out, tuple-major, floats only: bindings
// kProbeInputBinding and kProbeOutputBinding of the set after the last one the textures use
// (probe_set()), so they never meet a binding map's slots. One invocation per tuple, 64 per
// workgroup; the caller pads the tuple count to a multiple of 64. Textures and linear_clamp are
// bound as in the fragment stage. A compute stage has no implicit LOD and no derivatives: samples
// read level 0 (what a one-level texture gives a fragment too), and ddx / ddy are fine differences
// over quads of tuples 4k..4k+3 = pixels (0,0), (1,0), (0,1), (1,1) of a 2x2 quad, exchanged
// through workgroup memory: the CPU evaluator's lane quads.
constexpr uint32_t kProbeInputBinding = 0;
constexpr uint32_t kProbeOutputBinding = 1;
uint32_t probe_set(const ShaderInterface& in);
constexpr uint32_t kProbeWorkgroupSize = 64;

struct ProbeField {
    std::string name;
    Type type = Type::Float;
    uint32_t offset = 0; // in floats within a tuple
};

struct ProbeLayout {
    std::vector<ProbeField> inputs, outputs;
    uint32_t input_stride = 0, output_stride = 0; // floats per tuple
};

ProbeLayout probe_layout(const Graph& g);
EmittedShader emit_probe(const Graph& g, Language language, const std::string& file_name,
                         const std::string& variant_key, Diagnostics& diagnostics,
                         const EmitOptions& options = {});

// Fills Diagnostic::node from the line each diagnostic points at in `shader`.
void attribute_to_nodes(const EmittedShader& shader, Diagnostics& diagnostics);

// Skeleton text from templates/ (embedded at build time); "" if unknown.
std::string_view template_text(std::string_view name);

} // namespace watergen
