// Vulkan state both the engine library (VariantPipeline, HeadlessGpu) and the test runner
// (vulkan_render.cpp, vulkan_descriptors.cpp, vulkan_mesh.cpp) build the same way: the offscreen
// render pass, the fixed-function state of a fullscreen water draw and of a companion pass's
// grid (vertex input, points, additive blending), the clamp-to-edge sampler. Compiled into
// watergen_engine, which watergen_runtime links; not installed.
#pragma once

#include <vector>

#include <vulkan/vulkan.h>

namespace watergen::vk_state {

// The logical device with one queue of `family`; `features` is a VkPhysicalDeviceFeatures2 chain
// (or null), `layers` for loaders old enough to read device layers.
VkResult create_device(VkPhysicalDevice physical, uint32_t family, const void* features,
                       const std::vector<const char*>& extensions,
                       const std::vector<const char*>& layers, VkDevice* device);

// One colour attachment of `format` (RGBA32F for the water; a pass's target format, e.g.
// R32_SFLOAT, for a companion pass), cleared, left in TRANSFER_SRC_OPTIMAL. Its dependencies
// order a draw after the previous draw's writes and copy's reads (the same image drawn again)
// and the copy out after the colour writes.
VkResult create_offscreen_render_pass(VkDevice device, VkRenderPass* pass,
                                      VkFormat format = VK_FORMAT_R32G32B32A32_SFLOAT);

// Triangle list, filled, no culling (the generated triangle's winding does not matter), one
// sample, raw output (no blending: tests compare exact floats). Points into itself: keep it
// where it was made while the pipeline is created.
struct FixedFunction {
    FixedFunction();
    FixedFunction(const FixedFunction&) = delete;
    FixedFunction& operator=(const FixedFunction&) = delete;
    VkPipelineInputAssemblyStateCreateInfo assembly{};
    VkPipelineRasterizationStateCreateInfo raster{};
    VkPipelineMultisampleStateCreateInfo multisample{};
    VkPipelineColorBlendAttachmentState blend_attachment{};
    VkPipelineColorBlendStateCreateInfo blend{};
    // A point list (the vertex stage writes PointSize: Vulkan leaves the size undefined
    // otherwise).
    void points();
    // ONE + ONE on colour and alpha: passes that accumulate (caustics) add every fragment into a
    // target cleared to 0. The target's format must support blending (blendable()).
    void additive_blend();
    // Sets gci's sType and points its assembly, rasterization, multisample and blend state here.
    void apply(VkGraphicsPipelineCreateInfo& gci) const;
};

// Whether `format` can be a blended colour attachment (optimal tiling) on `physical`.
bool blendable(VkPhysicalDevice physical, VkFormat format);

// One interleaved float vertex buffer at binding 0, attribute i at location i with sizes[i]
// floats (1 to 4; the caller checks). Points into itself: keep it where it was made while the
// pipeline is created. Empty `sizes`: no vertex input (the fullscreen triangle).
struct VertexInput {
    explicit VertexInput(const std::vector<uint32_t>& sizes);
    VertexInput(const VertexInput&) = delete;
    VertexInput& operator=(const VertexInput&) = delete;
    VkVertexInputBindingDescription binding{};
    std::vector<VkVertexInputAttributeDescription> attributes;
    VkPipelineVertexInputStateCreateInfo info{};
};

// Clamp to edge on every axis, one mip level.
VkSamplerCreateInfo clamp_sampler_info(VkFilter filter);

} // namespace watergen::vk_state
