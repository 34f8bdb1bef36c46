// HeadlessDevice's one-submit draws, each an OffscreenDraw: a VariantPipeline's fullscreen
// triangle, and a companion pass (its grid and uniforms checked against the draw and the
// pipeline, the indexed draw with additive blending, the target read back as the water
// variant's texture).
#include "device_context.h"
#include "watergen/headless/offscreen_draw.h"
#include "watergen/runtime/pass_pipeline.h"

#include <fmt/format.h>

#include <algorithm>

namespace watergen {

using namespace headless_detail;

namespace {

// Draws once and reads back; nullopt and `error` on failure.
std::optional<std::vector<float>> draw_once(HeadlessDevice& device, const VariantPipeline& p,
                                            const DrawTarget& target, const DrawBindings& in,
                                            const DrawGeometry& geometry, std::string* error) {
    const auto draw = OffscreenDraw::create(device, p, target, in, geometry, error);
    if (!draw || !draw->submit(nullptr, error)) return std::nullopt;
    return draw->read_back(error);
}

// What of the grid the draw and the device decide; throws naming what does not fit. Whole
// vertices and triangles and the index range: OffscreenDraw checks them.
void check_grid(const PassDraw& draw, const PassGrid& grid, const VkPhysicalDeviceLimits& limits) {
    if (grid.texels != draw.texels)
        throw DeviceError(fmt::format("the grid is for {} texels; the draw's target has {} (make "
                                      "the grid with pass_grid() of this draw)",
                                      grid.texels, draw.texels));
    if (grid.points != (draw.primitive == "points"))
        throw DeviceError(
            fmt::format("the grid's primitive does not match draw.primitive '{}'", draw.primitive));
    const uint32_t side_limit = std::min(limits.maxFramebufferWidth, limits.maxImageDimension2D);
    if (grid.texels == 0 || grid.texels > side_limit)
        throw DeviceError(fmt::format("a target of {} texels; the device draws 1 to {}",
                                      grid.texels, side_limit));
    const size_t vertices = grid.vertices.size() / 2;
    if (vertices > kMaxPassGridVertices)
        throw DeviceError(fmt::format("the grid has {} vertices; expected at most 2^26 (a smaller "
                                      "margin or fewer texels)",
                                      vertices));
    if (grid.vertices.empty() || grid.indices.empty())
        throw DeviceError(fmt::format("the grid has {} vertex floats and {} indices; expected some",
                                      grid.vertices.size(), grid.indices.size()));
}

// Every supplied block names a uniform buffer or the push-constant block of the pipeline and
// has its packed size: the reflected size up to the next 16 bytes (UniformWriter::pack). A
// block the pipeline has but the caller left out: the descriptors (or the push constants) say
// so.
void check_uniforms(const VariantPipeline& p,
                    const std::map<std::string, std::vector<uint8_t>>& uniforms) {
    for (const auto& [name, bytes] : uniforms) {
        const DescriptorBinding* found = nullptr;
        std::string blocks;
        for (uint32_t s = 0; s < p.set_layouts().size(); ++s)
            for (const DescriptorBinding& b : p.bindings(s))
                if (b.kind == DescriptorKind::UniformBuffer) {
                    blocks += (blocks.empty() ? "" : ", ") + b.name;
                    if (b.name == name) found = &b;
                }
        if (const DescriptorBinding* push = p.push_constant()) {
            blocks += (blocks.empty() ? "" : ", ") + push->name + " (push constant)";
            if (push->name == name) found = push;
        }
        if (!found)
            throw DeviceError(fmt::format("uniform block '{}' is not one of the pass's ({})", name,
                                          blocks.empty() ? "none" : blocks));
        const size_t packed = (found->block_size + 15) / 16 * 16;
        if (bytes.size() < found->block_size || bytes.size() > packed)
            throw DeviceError(fmt::format(
                "uniform block '{}' is {} bytes; the pass's reflection packs it in {}{} "
                "(UniformWriter(pass.shader).pack() of the pass's vertex reflection)",
                name, bytes.size(), found->block_size,
                packed != found->block_size ? fmt::format(" to {}", packed) : ""));
    }
}

uint32_t channel_index(const std::string& channel, uint32_t channels) {
    const std::string names = "rgba";
    const size_t i = channel.size() == 1 ? names.find(channel[0]) : std::string::npos;
    if (i == std::string::npos || i >= channels)
        throw DeviceError(fmt::format("draw.channel '{}': expected one of the target's {} channels",
                                      channel, names.substr(0, channels)));
    return static_cast<uint32_t>(i);
}

} // namespace

std::vector<float> HeadlessDevice::draw(const VariantPipeline& pipeline, const HeadlessDraw& in,
                                        std::string* error) {
    const DrawTarget target{.width = in.width, .height = in.height};
    const DrawBindings bindings{
        .uniforms = &in.uniforms, .textures = &in.textures, .filter = in.filter};
    DrawGeometry geometry;
    if (in.indices && !in.vertices) {
        if (error) *error = "draw: indices without vertices";
        return {};
    }
    if (in.indices) {
        geometry.vertices = in.vertices;
        geometry.indices = in.indices;
        geometry.attribute_sizes = in.attribute_sizes;
        geometry.patch_control_points = in.patch_control_points;
    }
    auto texels = draw_once(*this, pipeline, target, bindings, geometry, error);
    return texels ? std::move(*texels) : std::vector<float>{};
}

std::optional<TextureData> HeadlessDevice::draw_pass(
    const VariantPipeline& pipeline, const PassDraw& draw, const PassGrid& grid,
    const std::map<std::string, std::vector<uint8_t>>& uniforms, std::string* error) {
    const auto format = pass_format(draw, error);
    if (!format || !render_pass(*format, error)) return std::nullopt;
    const uint32_t channels = pass_format_channels(*format);
    uint32_t channel = 0;
    const bool fits = guarded(*context_, error, [&] {
        check_grid(draw, grid, context_->limits);
        check_uniforms(pipeline, uniforms);
        channel = channel_index(draw.channel, channels);
    });
    if (!fits) return std::nullopt;

    const DrawTarget target{grid.texels, grid.texels, *format, static_cast<float>(draw.clear)};
    const DrawBindings bindings{.uniforms = &uniforms};
    const DrawGeometry geometry{&grid.vertices, &grid.indices, {2}, grid.points, "grid"};
    const auto texels = draw_once(*this, pipeline, target, bindings, geometry, error);
    if (!texels) return std::nullopt;
    TextureData t{grid.texels, grid.texels, 1, {}};
    t.rgba.resize(size_t(grid.texels) * grid.texels * 4);
    for (size_t p = 0; p < size_t(grid.texels) * grid.texels; ++p) {
        const float v = (*texels)[p * channels + channel];
        t.rgba[p * 4] = t.rgba[p * 4 + 1] = t.rgba[p * 4 + 2] = v;
        t.rgba[p * 4 + 3] = 1.0f;
    }
    return t;
}

} // namespace watergen
