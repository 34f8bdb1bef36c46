// A companion pass's target format and pipeline state, checked against its draw description
// and its vertex stage's reflection.
#include "watergen/runtime/pass_pipeline.h"

#include <array>
#include <utility>

namespace watergen {

namespace {

constexpr std::array<std::pair<const char*, VkFormat>, 3> kFormats = {{
    {"R32_SFLOAT", VK_FORMAT_R32_SFLOAT},
    {"R32G32_SFLOAT", VK_FORMAT_R32G32_SFLOAT},
    {"R32G32B32A32_SFLOAT", VK_FORMAT_R32G32B32A32_SFLOAT},
}};

} // namespace

std::optional<VkFormat> pass_format(const PassDraw& draw, std::string* error) {
    for (const auto& [name, format] : kFormats)
        if (draw.format == name) return format;
    *error = "draw.format '" + draw.format +
             "': expected R32_SFLOAT, R32G32_SFLOAT or R32G32B32A32_SFLOAT";
    return std::nullopt;
}

uint32_t pass_format_channels(VkFormat format) {
    switch (format) {
    case VK_FORMAT_R32_SFLOAT:
        return 1;
    case VK_FORMAT_R32G32_SFLOAT:
        return 2;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
        return 4;
    default:
        return 0;
    }
}

std::optional<PipelineGeometry> pass_geometry(const PassDraw& draw, const Reflection& vertex,
                                              std::string* error) {
    if (draw.attribute != "grid_xz") {
        *error = "draw.attribute '" + draw.attribute + "': expected grid_xz";
        return std::nullopt;
    }
    if (draw.primitive != "triangles" && draw.primitive != "points") {
        *error = "draw.primitive '" + draw.primitive + "': expected triangles or points";
        return std::nullopt;
    }
    if (draw.blend != "additive") {
        *error = "draw.blend '" + draw.blend + "': expected additive";
        return std::nullopt;
    }
    const bool vec2_at_0 = !vertex.inputs.empty() && vertex.inputs.front().location == 0 &&
                           vertex.inputs.front().type == "vec2";
    if (!vec2_at_0) {
        *error = "the pass's vertex stage has no vec2 input at location 0 for grid_xz (is this "
                 "the pass's vertex reflection?)";
        return std::nullopt;
    }
    PipelineGeometry g;
    g.attribute_sizes = {2};
    g.points = draw.primitive == "points";
    g.additive_blend = true;
    return g;
}

std::optional<VariantPipeline> create_pass_pipeline(VkDevice device, const PassDraw& draw,
                                                    const VariantPipelineDesc& desc,
                                                    std::string* error) {
    if (!desc.vertex_reflection) {
        *error = "VariantPipelineDesc: expected the pass's vertex reflection";
        return std::nullopt;
    }
    auto geometry = pass_geometry(draw, *desc.vertex_reflection, error);
    if (!geometry || !pass_format(draw, error)) return std::nullopt;
    return VariantPipeline::create(device, desc, *geometry, error);
}

} // namespace watergen
