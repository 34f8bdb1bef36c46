// The Vulkan side of a build's companion pass (build_pass.h) for an engine: the target format
// its draw description names, and its pipeline: a VariantPipeline made from the pass's SPIR-V
// and reflection (same descriptor layouts, same pipeline cache handling) with the grid's vertex
// input (the draw's attribute, grid_xz: a vec2 at location 0 in one buffer at binding 0), a
// triangle or point list, and ONE + ONE blending. Part of watergen::runtime.
//
// The engine then draws, each frame before the water: begin a render pass of one colour
// attachment of pass_format() (texels x texels, cleared to draw.clear), bind the pipeline, the
// block packed by UniformWriter(pass.shader) against the pass's vertex reflection, the vertex
// and index buffers of pass_grid(), vkCmdDrawIndexed(indices), and sample the result as the
// water variant's caustics_map (its draw.channel). HeadlessDevice::draw_pass()
// (watergen/headless/headless_device.h) does exactly that.
#pragma once

#include <optional>
#include <string>

#include <vulkan/vulkan.h>

#include "watergen/runtime/build_pass.h"
#include "watergen/runtime/variant_pipeline.h"

namespace watergen {

// The colour target's format: R32_SFLOAT, R32G32_SFLOAT or R32G32B32A32_SFLOAT (float targets
// the headless draw reads back as they are). nullopt and `error` naming the format otherwise.
std::optional<VkFormat> pass_format(const PassDraw& draw, std::string* error);
// Floats per texel of a pass_format() (1, 2 or 4); 0 for any other format.
uint32_t pass_format_channels(VkFormat format);

// The pipeline state of the draw: attribute grid_xz as a vec2, triangles or points, additive.
// nullopt and `error` for another attribute, primitive or blend, or a vertex stage whose
// reflection has no vec2 input at location 0.
std::optional<PipelineGeometry> pass_geometry(const PassDraw& draw, const Reflection& vertex,
                                              std::string* error);

// VariantPipeline::create with pass_geometry(draw, *desc.vertex_reflection).
// desc.render_pass must have one colour attachment of pass_format(draw) (blending into it must
// be supported: HeadlessDevice::render_pass(format) checks).
std::optional<VariantPipeline> create_pass_pipeline(VkDevice device, const PassDraw& draw,
                                                    const VariantPipelineDesc& desc,
                                                    std::string* error);

} // namespace watergen
