// Where each resource a water shader reads is bound, in every target: the engine's descriptor
// layout, not watergen's. One map serves every variant of a material (a resource a variant does
// not read keeps its slot), so one descriptor-set layout and one pipeline layout serve them all.
//
// A slot gives the Vulkan set and binding (GLSL layout(set, binding), HLSL [[vk::binding]]), the
// HLSL register and space (register(b0, space2): b for the uniform block, s for the sampler, t
// for a texture), the Metal index ([[buffer(n)]], [[sampler(n)]], [[texture(n)]], which
// SPIRV-Cross writes) and the GL binding point or texture unit (GLSL 330 and ESSL 300 cannot
// spell one, so the engine sets it: glUniformBlockBinding, glUniform1i). Maps come from a
// profile (water/binding_profiles.h) or a JSON file (plan/binding_map_file.h).
//
// The parameter block may instead be a push constant (kind PushConstant): GLSL
// layout(push_constant, std140), HLSL [[vk::push_constant]] cbuffer, the same offsets as the
// uniform block. It has no set, binding or HLSL register (glslang 12 decorates a push-constant
// cbuffer that names a register with a DescriptorSet, which spirv-val rejects: VUID-
// StandaloneSpirv-DescriptorSet-06491); Metal and GL still get a buffer index and a uniform
// block binding (SPIRV-Cross writes it as a buffer / a uniform block there). The map states the
// range's size, push_constant_bytes, and every variant's block must fit in it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace watergen {

enum class ResourceKind { UniformBlock, Sampler, Texture, PushConstant };
// "uniform_block", "sampler", "texture", "push_constant"
const char* to_string(ResourceKind kind);
std::optional<ResourceKind> parse_resource_kind(const std::string& word);

// The resource names the emitters declare: the parameter block and the one sampler; every other
// name is a texture.
constexpr const char* kParamsResource = "WaterParams";
constexpr const char* kSamplerResource = "linear_clamp";
ResourceKind default_resource_kind(const std::string& name);

// Vulkan guarantees 128 bytes of push constants (maxPushConstantsSize); desktop drivers give 256
// (RADV, NVIDIA), Apple's 4096, the most any device reports.
constexpr uint32_t kGuaranteedPushConstantBytes = 128;
constexpr uint32_t kMaxPushConstantBytes = 4096;

struct ResourceSlot {
    std::string name;
    ResourceKind kind = ResourceKind::Texture;
    uint32_t set = 0, binding = 0;
    uint32_t hlsl_register = 0, hlsl_space = 0;
    uint32_t msl_index = 0;
    uint32_t gl_unit = 0;
    std::string origin =
        ""; // where it was defined, for messages: "map.json:12" or "profile watergen"
};

struct BindingConflict {
    std::string message; // names both resources and where each was defined
    size_t later = 0;    // the index in BindingMap::slots of the second of the two
};

struct BindingMap {
    std::string name; // the profile's name, or the file the map was read from
    std::vector<ResourceSlot> slots;
    // The push-constant range of a map with a PushConstant slot: at most
    // kMaxPushConstantBytes, a multiple of 16 (the block is whole 16-byte registers). A variant
    // whose block is larger is an error naming both sizes.
    uint32_t push_constant_bytes = kGuaranteedPushConstantBytes;

    const ResourceSlot* find(const std::string& resource) const;
    const ResourceSlot* push_constant() const; // the PushConstant slot, if any
    // The first two slots that claim one place in one target (or one name twice, or two push
    // constants); nullopt when none clash.
    std::optional<BindingConflict> conflict() const;
};

// Whether every error among `diagnostics` is the map's (an emitter's: a resource it places no
// slot for, or as another kind, a push-constant range too small), and there is one: a build
// that fails only so is refused as bad input, the map being an input.
struct Diagnostic;
bool only_binding_map_errors(const std::vector<Diagnostic>& diagnostics, const BindingMap* map);

} // namespace watergen
