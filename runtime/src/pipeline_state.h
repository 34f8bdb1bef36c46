// The fixed-function and vertex-input state of a VariantPipeline (variant_pipeline.cpp): a
// fullscreen water draw, or a companion pass's grid (vertex input, points, additive blending).
// Private to watergen_runtime; not installed.
#pragma once

#include <vector>

#include <vulkan/vulkan.h>

namespace watergen::vk_state {

// Triangle list, filled, no culling (the generated triangle's winding does not matter; `raster`
// may ask for it), one
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
    VkPipelineTessellationStateCreateInfo tessellation{};
    // A point list (the vertex stage writes PointSize: Vulkan leaves the size undefined
    // otherwise).
    void points();
    // A patch list of `control_points` points each, for tessellation stages.
    void patches(uint32_t control_points);
    // ONE + ONE on colour and alpha: passes that accumulate (caustics) add every fragment into a
    // target cleared to 0. The target's format must support blending.
    void additive_blend();
    // Sets gci's sType and points its assembly, rasterization, multisample and blend state here
    // (and its tessellation state, for patches).
    void apply(VkGraphicsPipelineCreateInfo& gci) const;
};

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

} // namespace watergen::vk_state
