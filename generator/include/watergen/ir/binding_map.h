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
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace watergen {

enum class ResourceKind { UniformBlock, Sampler, Texture };
const char* to_string(ResourceKind kind); // "uniform_block", "sampler", "texture"
std::optional<ResourceKind> parse_resource_kind(const std::string& word);

// The resource names the emitters declare: the parameter block and the one sampler; every other
// name is a texture.
constexpr const char* kParamsResource = "WaterParams";
constexpr const char* kSamplerResource = "linear_clamp";
ResourceKind default_resource_kind(const std::string& name);

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

    const ResourceSlot* find(const std::string& resource) const;
    // The first two slots that claim one place in one target (or one name twice); nullopt
    // when none clash.
    std::optional<BindingConflict> conflict() const;
};

} // namespace watergen
