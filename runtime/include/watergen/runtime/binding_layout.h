// One descriptor layout for every variant of a build: the descriptor set layouts and the
// pipeline layout of the build's binding map (manifest "bindings", ShaderBuild::bindings()),
// made once. VariantPipelineDesc::layout hands it to every pipeline of the build, so the engine
// allocates descriptor sets of one layout and keeps them bound across variants. Part of
// watergen::runtime.
//
// Every slot of the map is in the layout, whether a variant reads it or not (a descriptor a
// pipeline does not read need not be written); each binding is visible to the vertex and the
// fragment stage. Sets without a slot below the last get empty layouts.
//
// A push-constant slot (the parameter block as a push constant) takes no descriptor: it is in
// no set layout and no pool size; the pipeline layout instead has one push-constant range of
// the map's push_constant_bytes at offset 0, visible to the vertex and the fragment stage
// (vkCmdPushConstants must then name both stages).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "watergen/runtime/reflection.h"

namespace watergen {

// Vulkan guarantees maxBoundDescriptorSets >= 4: a layout has sets 0..3 at most.
constexpr uint32_t kMaxDescriptorSets = 4;
// Vulkan guarantees maxPushConstantsSize >= 128; no device reports more than 4096 (Apple's),
// the most a map's push_constant_bytes may state.
constexpr uint32_t kGuaranteedPushConstantsSize = 128;
constexpr uint32_t kMaxPushConstantRange = 4096;

// One resource of the map, as the manifest records it.
struct MapSlot {
    std::string name;
    // UniformBuffer, Sampler or SampledImage (uniform block, sampler, texture), or
    // PushConstant: the parameter block as a push constant, no descriptor.
    DescriptorKind kind = DescriptorKind::SampledImage;
    uint32_t set = 0, binding = 0;              // 0 for a push constant (it has none)
    uint32_t hlsl_register = 0, hlsl_space = 0; // 0 for a push constant
    uint32_t msl = 0, gl = 0;                   // Metal index; GL binding point or texture unit
};

struct BuildBindings {
    std::string map; // the profile's name, or the map file's
    std::vector<MapSlot> slots;
    // Bytes of the push-constant range the map states (manifest "push_constant_bytes"): a
    // multiple of 4, 4..kMaxPushConstantRange, at least every variant's block (the generator
    // checks); 0 without one. Only a map with a push-constant slot has one.
    uint32_t push_constant_bytes = 0;
    const MapSlot* find(const std::string& name) const;
};

class BindingLayout {
  public:
    // std::nullopt and `error` naming the Vulkan call and its VkResult, or a map the layout
    // cannot hold (none, a set past 3, two slots at one binding, two push-constant slots, a
    // push-constant range that is not a multiple of 4 or is larger than
    // `max_push_constants_size`). `max_push_constants_size`: the device's
    // VkPhysicalDeviceLimits::maxPushConstantsSize; the default is the 128 bytes every Vulkan
    // device has, so it is never wrong, only stricter than a device may need.
    static std::optional<BindingLayout>
    create(VkDevice device, const BuildBindings& bindings, std::string* error,
           uint32_t max_push_constants_size = kGuaranteedPushConstantsSize);
    BindingLayout(BindingLayout&& other) noexcept;
    BindingLayout& operator=(BindingLayout&& other) noexcept;
    BindingLayout(const BindingLayout&) = delete;
    BindingLayout& operator=(const BindingLayout&) = delete;
    ~BindingLayout();

    VkPipelineLayout layout() const { return layout_; }
    const std::vector<VkDescriptorSetLayout>& set_layouts() const { return set_layouts_; }
    // Descriptor counts for a pool holding `copies` of every set.
    std::vector<VkDescriptorPoolSize> pool_sizes(uint32_t copies = 1) const;
    // The pipeline layout's push-constant range (offset 0, push_constant_bytes, vertex and
    // fragment stages); null when the map has none.
    const VkPushConstantRange* push_constant_range() const {
        return push_range_.size ? &push_range_ : nullptr;
    }
    // The name of the map's push-constant slot ("WaterParams"); "" without one.
    const std::string& push_constant_block() const { return push_block_; }
    // "" when every descriptor `r` declares is a slot of the map (same name, set, binding and
    // kind) and its push-constant block, if any, is the map's push-constant slot and fits the
    // range; else the first that is not, named.
    std::string check(const Reflection& r) const;

  private:
    BindingLayout() = default;
    void destroy();
    VkDevice device_ = VK_NULL_HANDLE;
    BuildBindings bindings_;
    std::vector<VkDescriptorSetLayout> set_layouts_;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPushConstantRange push_range_{}; // size 0: none
    std::string push_block_;
};

} // namespace watergen
