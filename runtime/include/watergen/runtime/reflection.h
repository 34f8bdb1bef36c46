// Shader interface as an engine (and the headless device) needs it: which descriptors a stage
// binds and where each uniform lives inside its block. Produced by the generator from
// SPIRV-Cross reflection, stored as JSON next to every shader.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace watergen {

// TessControl / TessEvaluation: the displaced-geometry path's patch stages (GLSL tesc / tese,
// HLSL hull / domain).
enum class ShaderStage { Vertex, Fragment, Compute, TessControl, TessEvaluation };

struct UniformMember {
    std::string name;    // as declared in the source, e.g. "sun_direction"
    std::string type;    // GLSL spelling: float, vec2, vec3, vec4, mat3, mat4, int, uint
    uint32_t offset = 0; // bytes from the start of the block
    uint32_t size = 0;   // bytes
    // Arrays: elements and bytes between consecutive ones; both 0 for a non-array member.
    uint32_t array_size = 0;
    uint32_t array_stride = 0;
};

enum class DescriptorKind {
    UniformBuffer,
    StorageBuffer,
    SampledImage,
    Sampler,
    CombinedImageSampler,
    // A push-constant block (Reflection::push_constant): bytes recorded into the command buffer
    // with vkCmdPushConstants, not a descriptor; set and binding are 0.
    PushConstant
};

struct DescriptorBinding {
    std::string name; // variable or block name in the source
    uint32_t set = 0;
    uint32_t binding = 0;
    DescriptorKind kind = DescriptorKind::UniformBuffer;
    std::string image_dim;              // "2D" or "Cube" for images, "" otherwise
    uint32_t block_size = 0;            // bytes, for buffers
    std::vector<UniformMember> members; // for buffers
};

struct StageVariable {
    std::string name;
    uint32_t location = 0;
    std::string type;
};

// A scalar specialization constant: set at pipeline creation (VkSpecializationInfo) by id.
struct SpecializationConstant {
    uint32_t id = 0;            // constant_id (SpecId)
    std::string name;           // as declared, e.g. "sun_direction_x" for a vector's component
    std::string type;           // GLSL spelling: float, int, uint, bool
    double default_value = 0.0; // the value the module holds (float / int / uint / 0 or 1)
    // Valid range of the parameter it stands for (generator: Parameter::min / max); both 0
    // when unknown.
    double min = 0.0, max = 0.0;
};

struct Reflection {
    ShaderStage stage = ShaderStage::Fragment;
    std::string entry_point = "main";
    std::vector<DescriptorBinding> bindings; // sorted by (set, binding)
    // The stage's push-constant block (kind PushConstant, block_size and members as a uniform
    // block's), when a binding map makes the parameter block one; never among `bindings`.
    std::optional<DescriptorBinding> push_constant;
    std::vector<StageVariable> inputs;                            // sorted by location
    std::vector<StageVariable> outputs;                           // sorted by location
    std::vector<SpecializationConstant> specialization_constants; // sorted by id
};

// Deterministic JSON (sorted, 2-space indent, trailing newline).
std::string reflection_to_json(const Reflection& r);
// Returns std::nullopt and sets `error` ("key: what was expected") on malformed input.
std::optional<Reflection> reflection_from_json(const std::string& text, std::string* error);

const char* to_string(ShaderStage s);
// "vert" / "frag" / "comp" / "tesc" / "tese": the stage in file names (water.frag.spv) and tool
// flags.
const char* stage_tag(ShaderStage s);
const char* to_string(DescriptorKind k);

} // namespace watergen
