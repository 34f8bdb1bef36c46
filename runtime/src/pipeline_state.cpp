// The fixed-function and vertex-input state of a VariantPipeline (see pipeline_state.h).
#include "pipeline_state.h"

namespace watergen::vk_state {

FixedFunction::FixedFunction() {
    assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    raster.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE;
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.lineWidth = 1.0f;
    multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    blend_attachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                      VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
    blend.attachmentCount = 1;
    blend.pAttachments = &blend_attachment;
}

void FixedFunction::points() {
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
}

void FixedFunction::patches(uint32_t control_points) {
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_PATCH_LIST;
    tessellation.sType = VK_STRUCTURE_TYPE_PIPELINE_TESSELLATION_STATE_CREATE_INFO;
    tessellation.patchControlPoints = control_points;
}

void FixedFunction::additive_blend() {
    VkPipelineColorBlendAttachmentState& b = blend_attachment;
    b.blendEnable = VK_TRUE;
    b.srcColorBlendFactor = b.dstColorBlendFactor = VK_BLEND_FACTOR_ONE;
    b.srcAlphaBlendFactor = b.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    b.colorBlendOp = b.alphaBlendOp = VK_BLEND_OP_ADD;
}

VertexInput::VertexInput(const std::vector<uint32_t>& sizes) {
    static constexpr VkFormat kFloatFormats[] = {VK_FORMAT_R32_SFLOAT, VK_FORMAT_R32G32_SFLOAT,
                                                 VK_FORMAT_R32G32B32_SFLOAT,
                                                 VK_FORMAT_R32G32B32A32_SFLOAT};
    info.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
    if (sizes.empty()) return;
    uint32_t offset = 0;
    for (uint32_t i = 0; i < sizes.size(); ++i) {
        attributes.push_back({i, 0, kFloatFormats[sizes[i] - 1], offset});
        offset += sizes[i] * uint32_t(sizeof(float));
    }
    binding = {0, offset, VK_VERTEX_INPUT_RATE_VERTEX};
    info.vertexBindingDescriptionCount = 1;
    info.pVertexBindingDescriptions = &binding;
    info.vertexAttributeDescriptionCount = static_cast<uint32_t>(attributes.size());
    info.pVertexAttributeDescriptions = attributes.data();
}

void FixedFunction::apply(VkGraphicsPipelineCreateInfo& gci) const {
    gci.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
    gci.pInputAssemblyState = &assembly;
    gci.pRasterizationState = &raster;
    gci.pMultisampleState = &multisample;
    gci.pColorBlendState = &blend;
    gci.pTessellationState =
        assembly.topology == VK_PRIMITIVE_TOPOLOGY_PATCH_LIST ? &tessellation : nullptr;
}

} // namespace watergen::vk_state
