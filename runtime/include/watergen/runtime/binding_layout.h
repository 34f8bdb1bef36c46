// One descriptor layout for every variant of a build: the descriptor set layouts and the
// pipeline layout of the build's binding map (manifest "bindings", ShaderBuild::bindings()),
// made once. VariantPipelineDesc::layout hands it to every pipeline of the build, so the engine
// allocates descriptor sets of one layout and keeps them bound across variants. Part of
// watergen::runtime.
//
// Every slot of the map is in the layout, whether a variant reads it or not (a descriptor a
// pipeline does not read need not be written); each binding is visible to the vertex and the
// fragment stage. Sets without a slot below the last get empty layouts.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "watergen/runtime/reflection.h"

namespace watergen {

// Vulkan guarantees maxBoundDescriptorSets >= 4: a layout has sets 0..3 at most.
constexpr uint32_t kMaxDescriptorSets = 4;

// One resource of the map, as the manifest records it.
struct MapSlot {
    std::string name;
    DescriptorKind kind = DescriptorKind::SampledImage; // uniform block, sampler or texture
    uint32_t set = 0, binding = 0;
    uint32_t hlsl_register = 0, hlsl_space = 0;
    uint32_t msl = 0, gl = 0; // Metal index; GL binding point or texture unit
};

struct BuildBindings {
    std::string map; // the profile's name, or the map file's
    std::vector<MapSlot> slots;
    const MapSlot* find(const std::string& name) const;
};

class BindingLayout {
  public:
    // std::nullopt and `error` naming the Vulkan call and its VkResult, or a map the layout
    // cannot hold (none, a set past 3, two slots at one binding).
    static std::optional<BindingLayout> create(VkDevice device, const BuildBindings& bindings,
                                               std::string* error);
    BindingLayout(BindingLayout&& other) noexcept;
    BindingLayout& operator=(BindingLayout&& other) noexcept;
    BindingLayout(const BindingLayout&) = delete;
    BindingLayout& operator=(const BindingLayout&) = delete;
    ~BindingLayout();

    VkPipelineLayout layout() const { return layout_; }
    const std::vector<VkDescriptorSetLayout>& set_layouts() const { return set_layouts_; }
    // Descriptor counts for a pool holding `copies` of every set.
    std::vector<VkDescriptorPoolSize> pool_sizes(uint32_t copies = 1) const;
    // "" when every descriptor `r` declares is a slot of the map (same name, set, binding and
    // kind); else the first that is not, named.
    std::string check(const Reflection& r) const;

  private:
    BindingLayout() = default;
    void destroy();
    VkDevice device_ = VK_NULL_HANDLE;
    BuildBindings bindings_;
    std::vector<VkDescriptorSetLayout> set_layouts_;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
};

} // namespace watergen
