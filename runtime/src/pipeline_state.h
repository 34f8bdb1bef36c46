// Vulkan state both the engine library (VariantPipeline, HeadlessGpu) and the test runner
// (vulkan_render.cpp, vulkan_descriptors.cpp) build the same way: the offscreen render pass,
// the fixed-function state of a fullscreen water draw, the clamp-to-edge sampler. Compiled into
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

// One RGBA32F colour attachment, cleared, left in TRANSFER_SRC_OPTIMAL. Its dependencies order a
// draw after the previous draw's writes and copy's reads (the same image drawn again) and the
// copy out after the colour writes.
VkResult create_offscreen_render_pass(VkDevice device, VkRenderPass* pass);

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
    // Sets gci's sType and points its assembly, rasterization, multisample and blend state here.
    void apply(VkGraphicsPipelineCreateInfo& gci) const;
};

// Clamp to edge on every axis, one mip level.
VkSamplerCreateInfo clamp_sampler_info(VkFilter filter);

} // namespace watergen::vk_state
