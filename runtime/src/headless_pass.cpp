// HeadlessGpu's draw of a companion pass: its render pass per target format, the grid and
// uniforms checked against the draw and the pipeline, the indexed draw with additive blending,
// the target read back as the water variant's texture.
#include <algorithm>

#include "headless_frame.h"
#include "pipeline_state.h"
#include "watergen/runtime/headless_gpu.h"
#include "watergen/runtime/pass_pipeline.h"

namespace watergen {

using namespace headless;

namespace {

// The grid against the draw and the device; throws a DrawError naming what does not fit.
void check_grid(const PassDraw& draw, const PassGrid& grid, const VkPhysicalDeviceLimits& limits) {
    if (grid.texels != draw.texels)
        throw DrawError("the grid is for " + std::to_string(grid.texels) +
                        " texels; the draw's target has " + std::to_string(draw.texels) +
                        " (make the grid with pass_grid() of this draw)");
    if (grid.points != (draw.primitive == "points"))
        throw DrawError("the grid's primitive does not match draw.primitive '" + draw.primitive +
                        "'");
    const uint32_t side_limit = std::min(limits.maxFramebufferWidth, limits.maxImageDimension2D);
    if (grid.texels == 0 || grid.texels > side_limit)
        throw DrawError("a target of " + std::to_string(grid.texels) +
                        " texels; the device draws 1 to " + std::to_string(side_limit));
    const size_t vertices = grid.vertices.size() / 2;
    if (grid.vertices.empty() || grid.vertices.size() % 2 != 0)
        throw DrawError("the grid has " + std::to_string(grid.vertices.size()) +
                        " floats; expected two (grid_xz) per vertex");
    if (vertices > kMaxPassGridVertices)
        throw DrawError("the grid has " + std::to_string(vertices) +
                        " vertices; expected at most 2^26 (a smaller margin or fewer texels)");
    if (grid.indices.empty() || (!grid.points && grid.indices.size() % 3 != 0))
        throw DrawError("the grid has " + std::to_string(grid.indices.size()) + " indices; " +
                        (grid.points ? "expected at least one" : "expected whole triangles"));
    const uint32_t largest = *std::max_element(grid.indices.begin(), grid.indices.end());
    if (largest >= vertices)
        throw DrawError("grid index " + std::to_string(largest) + " is past its " +
                        std::to_string(vertices) + " vertices");
}

// Every supplied block names a uniform buffer of the pipeline and has its packed size: the
// reflected size up to the next 16 bytes (UniformWriter::pack). A block the pipeline has but
// the caller left out: descriptor_sets() says so.
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
        if (!found)
            throw DrawError("uniform block '" + name + "' is not one of the pass's (" +
                            (blocks.empty() ? "none" : blocks) + ")");
        const size_t packed = (found->block_size + 15) / 16 * 16;
        if (bytes.size() < found->block_size || bytes.size() > packed)
            throw DrawError("uniform block '" + name + "' is " + std::to_string(bytes.size()) +
                            " bytes; the pass's reflection packs it in " +
                            std::to_string(found->block_size) +
                            (packed != found->block_size ? " to " + std::to_string(packed) : "") +
                            " (UniformWriter(pass.shader).pack() of the pass's vertex reflection)");
    }
}

uint32_t channel_index(const std::string& channel, uint32_t channels) {
    const std::string names = "rgba";
    const size_t i = channel.size() == 1 ? names.find(channel[0]) : std::string::npos;
    if (i == std::string::npos || i >= channels)
        throw DrawError("draw.channel '" + channel + "': expected one of the target's " +
                        names.substr(0, channels) + " channels");
    return static_cast<uint32_t>(i);
}

} // namespace

VkRenderPass HeadlessGpu::render_pass(VkFormat format, std::string* error) {
    if (const auto it = target_passes_.find(format); it != target_passes_.end()) return it->second;
    if (!vk_state::blendable(physical_, format)) {
        *error = "device '" + device_name_ + "' cannot blend into VkFormat " +
                 std::to_string(static_cast<int>(format)) + " (a pass adds its fragments)";
        return VK_NULL_HANDLE;
    }
    VkRenderPass pass = VK_NULL_HANDLE;
    if (VkResult r = vk_state::create_offscreen_render_pass(device_, &pass, format);
        r != VK_SUCCESS) {
        *error = "vkCreateRenderPass failed: VkResult " + std::to_string(static_cast<int>(r));
        return VK_NULL_HANDLE;
    }
    target_passes_[format] = pass;
    return pass;
}

std::optional<HeadlessTexture>
HeadlessGpu::draw_pass(const VariantPipeline& pipeline, const PassDraw& draw, const PassGrid& grid,
                       const std::map<std::string, std::vector<uint8_t>>& uniforms,
                       std::string* error) {
    const auto format = pass_format(draw, error);
    if (!format) return std::nullopt;
    const VkRenderPass pass = render_pass(*format, error);
    if (!pass) return std::nullopt;
    try {
        VkPhysicalDeviceProperties props{};
        vkGetPhysicalDeviceProperties(physical_, &props);
        check_grid(draw, grid, props.limits);
        check_uniforms(pipeline, uniforms);
        const uint32_t channels = pass_format_channels(*format);
        const uint32_t channel = channel_index(draw.channel, channels);

        Frame f(physical_, device_);
        VkCommandBuffer cmd = begin_commands(f, pool_);
        HeadlessDraw inputs;
        inputs.uniforms = uniforms;
        const std::vector<VkDescriptorSet> sets = descriptor_sets(f, cmd, pipeline, inputs);
        const VkBuffer vertices =
            f.buffer(grid.vertices.size() * sizeof(float), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                     grid.vertices.data(), nullptr);
        const VkBuffer indices =
            f.buffer(grid.indices.size() * sizeof(uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT,
                     grid.indices.data(), nullptr);
        const Target target = make_target(f, pass, grid.texels, grid.texels, *format);
        begin_draw(cmd, pass, target, static_cast<float>(draw.clear), pipeline, sets);
        const VkDeviceSize offset = 0;
        vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &offset);
        vkCmdBindIndexBuffer(cmd, indices, 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, static_cast<uint32_t>(grid.indices.size()), 1, 0, 0, 0);
        vkCmdEndRenderPass(cmd);
        const std::vector<float> texels = read_target(f, queue_, cmd, target, channels);

        HeadlessTexture t{grid.texels, grid.texels, 1, {}};
        t.rgba.resize(size_t(grid.texels) * grid.texels * 4);
        for (size_t p = 0; p < size_t(grid.texels) * grid.texels; ++p) {
            const float v = texels[p * channels + channel];
            t.rgba[p * 4] = t.rgba[p * 4 + 1] = t.rgba[p * 4 + 2] = v;
            t.rgba[p * 4 + 3] = 1.0f;
        }
        return t;
    } catch (const DrawError& e) {
        *error = e.what();
        return std::nullopt;
    }
}

} // namespace watergen
