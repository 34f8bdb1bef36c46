// One draw of a VariantPipeline into an offscreen target, prepared once and submitted as often
// as asked (see offscreen_draw.h): target, descriptors, push constants, vertex and index
// buffers, timestamp queries, the recorded command buffer; the readback.
#include "watergen/headless/offscreen_draw.h"

#include "descriptors.h"
#include "watergen/runtime/pass_pipeline.h"

#include <fmt/format.h>

#include <algorithm>

namespace watergen {

namespace headless_detail {

struct PreparedDraw {
    explicit PreparedDraw(Context& ctx) : scope(ctx) {}
    Scope scope;
    DrawTarget target;
    Image image;
    BoundDescriptors descriptors;
    // The push-constant block's bytes and stages, recorded by vkCmdPushConstants; kept with
    // the draw so the recorded command buffer never refers to the caller's memory.
    std::vector<uint8_t> push_bytes;
    VkShaderStageFlags push_stages = 0;
    Buffer vertices, indices;
    uint32_t index_count = 0;             // 0: the fullscreen triangle
    VkQueryPool queries = VK_NULL_HANDLE; // null without timestamp support
    VkCommandBuffer draw = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
};

} // namespace headless_detail

using namespace headless_detail;

namespace {

// Throws naming what does not fit: attributes, whole vertices, whole triangles, index range.
void check_geometry(const DrawGeometry& g) {
    const std::string& what = g.what;
    if (g.attribute_sizes.empty())
        throw DeviceError(fmt::format("{} has indices but no vertex attributes", what));
    uint32_t stride = 0;
    for (size_t i = 0; i < g.attribute_sizes.size(); ++i) {
        if (g.attribute_sizes[i] < 1 || g.attribute_sizes[i] > 4)
            throw DeviceError(fmt::format("{} attribute {} has {} floats; 1 to 4 are supported",
                                          what, i, g.attribute_sizes[i]));
        stride += g.attribute_sizes[i];
    }
    const size_t floats = g.vertices ? g.vertices->size() : 0;
    if (floats == 0 || floats % stride != 0)
        throw DeviceError(
            fmt::format("{} has {} vertex floats, not a whole number of {}-float vertices", what,
                        floats, stride));
    if (g.patch_control_points && g.indices->size() % g.patch_control_points != 0)
        throw DeviceError(fmt::format("{} has {} indices, not whole patches of {}", what,
                                      g.indices->size(), g.patch_control_points));
    if (!g.points && !g.patch_control_points && g.indices->size() % 3 != 0)
        throw DeviceError(
            fmt::format("{} has {} indices, not whole triangles", what, g.indices->size()));
    const size_t vertex_count = floats / stride;
    const uint32_t largest = *std::max_element(g.indices->begin(), g.indices->end());
    if (largest >= vertex_count)
        throw DeviceError(
            fmt::format("{} index {} is past its {} vertices", what, largest, vertex_count));
}

VkRenderPass target_pass(const Context& ctx, VkFormat format) {
    const auto it = ctx.render_passes.find(format);
    if (it == ctx.render_passes.end())
        throw DeviceError(fmt::format("no render pass of VkFormat {} yet: make the pipeline with "
                                      "HeadlessDevice::render_pass(format)",
                                      static_cast<int>(format)));
    return it->second;
}

VkFramebuffer create_framebuffer(Scope& scope, VkRenderPass pass, const Image& target) {
    VkFramebufferCreateInfo fci{};
    fci.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    fci.renderPass = pass;
    fci.attachmentCount = 1;
    fci.pAttachments = &target.view;
    fci.width = target.width;
    fci.height = target.height;
    fci.layers = 1;
    VkFramebuffer fb = VK_NULL_HANDLE;
    VkDevice device = scope.ctx().device;
    check(vkCreateFramebuffer(device, &fci, nullptr, &fb), "vkCreateFramebuffer");
    scope.defer([device, fb] { vkDestroyFramebuffer(device, fb, nullptr); });
    return fb;
}

VkQueryPool create_timestamp_pool(Scope& scope) {
    VkQueryPoolCreateInfo qci{};
    qci.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
    qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qci.queryCount = 2;
    VkQueryPool pool = VK_NULL_HANDLE;
    VkDevice device = scope.ctx().device;
    check(vkCreateQueryPool(device, &qci, nullptr, &pool), "vkCreateQueryPool");
    scope.defer([device, pool] { vkDestroyQueryPool(device, pool, nullptr); });
    return pool;
}

// One command buffer, resubmitted for every draw: the render pass over the whole target
// (cleared), the pipeline, its sets and push constants, viewport and scissor, the triangle or
// the indexed list.
void record(PreparedDraw& p, const VariantPipeline& pipeline, VkRenderPass pass,
            VkFramebuffer framebuffer) {
    const uint32_t width = p.target.width, height = p.target.height;
    VkCommandBuffer cmd = p.draw = allocate_command_buffer(p.scope);
    begin_commands(cmd, false);
    if (p.queries) {
        vkCmdResetQueryPool(cmd, p.queries, 0, 2);
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, p.queries, 0);
    }
    const float c = p.target.clear;
    VkClearValue clear{};
    clear.color = {{c, c, c, c}};
    VkRenderPassBeginInfo rbi{};
    rbi.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    rbi.renderPass = pass;
    rbi.framebuffer = framebuffer;
    rbi.renderArea = {{0, 0}, {width, height}};
    rbi.clearValueCount = 1;
    rbi.pClearValues = &clear;
    vkCmdBeginRenderPass(cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.pipeline());
    const VkViewport viewport{0, 0, float(width), float(height), 0, 1};
    const VkRect2D scissor{{0, 0}, {width, height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    const std::vector<VkDescriptorSet>& sets = p.descriptors.sets;
    if (!sets.empty())
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.layout(), 0,
                                static_cast<uint32_t>(sets.size()), sets.data(), 0, nullptr);
    if (!p.push_bytes.empty())
        vkCmdPushConstants(cmd, pipeline.layout(), p.push_stages, 0,
                           static_cast<uint32_t>(p.push_bytes.size()), p.push_bytes.data());
    if (p.index_count) {
        const VkDeviceSize offset = 0;
        vkCmdBindVertexBuffers(cmd, 0, 1, &p.vertices.buffer, &offset);
        vkCmdBindIndexBuffer(cmd, p.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, p.index_count, 1, 0, 0, 0);
    } else {
        vkCmdDraw(cmd, 3, 1, 0, 0);
    }
    vkCmdEndRenderPass(cmd);
    // Bottom of pipe: the sample is taken once the draw has fully completed.
    if (p.queries) vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, p.queries, 1);
    check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
}

void prepare(PreparedDraw& p, const VariantPipeline& pipeline, const DrawBindings& bindings,
             const DrawGeometry& geometry) {
    Scope& scope = p.scope;
    Context& ctx = scope.ctx();
    const VkRenderPass pass = target_pass(ctx, p.target.format);
    const bool indexed = geometry.indices && !geometry.indices->empty();
    if (indexed) check_geometry(geometry);
    p.image = create_color_target(scope, p.target.width, p.target.height, p.target.format);
    SetBindings set_bindings;
    for (uint32_t s = 0; s < pipeline.set_layouts().size(); ++s)
        set_bindings.push_back(pipeline.bindings(s));
    DescriptorInputs inputs;
    inputs.uniforms = bindings.uniforms;
    inputs.sole_uniforms = bindings.sole_uniforms;
    inputs.textures = bindings.textures;
    inputs.filter = bindings.filter;
    inputs.push_constant = pipeline.push_constant();
    if (inputs.push_constant) {
        p.push_bytes = push_constant_bytes(ctx, *inputs.push_constant,
                                           pipeline.push_constant_size(), set_bindings, inputs);
        p.push_stages = pipeline.push_constant_stages();
    }
    const std::vector<VkDescriptorPoolSize> pool = pipeline.pool_sizes();
    p.descriptors = bind_descriptors(scope, pipeline.set_layouts(), set_bindings, inputs, &pool);
    const VkFramebuffer framebuffer = create_framebuffer(scope, pass, p.image);
    if (indexed) {
        // Host-visible like every buffer here; host writes before the submit need no barrier.
        p.vertices = upload_buffer(scope, geometry.vertices->data(),
                                   geometry.vertices->size() * sizeof(float),
                                   VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        p.indices = upload_buffer(scope, geometry.indices->data(),
                                  geometry.indices->size() * sizeof(uint32_t),
                                  VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
        p.index_count = static_cast<uint32_t>(geometry.indices->size());
    }
    if (ctx.timestamp_mask != 0) p.queries = create_timestamp_pool(scope);
    record(p, pipeline, pass, framebuffer);
    p.fence = create_fence(scope);
}

// The draw's time: GPU timestamps, or the CPU wall time of submit + wait without them.
double timed_submit(PreparedDraw& p) {
    Context& ctx = p.scope.ctx();
    const auto start = Clock::now();
    submit_and_wait(ctx, p.draw, p.fence);
    const double wall_ms = ms_since(start);
    if (!p.queries) return wall_ms;
    uint64_t ticks[2] = {};
    check(vkGetQueryPoolResults(ctx.device, p.queries, 0, 2, sizeof(ticks), ticks, sizeof(uint64_t),
                                VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
          "vkGetQueryPoolResults");
    const uint64_t delta = (ticks[1] - ticks[0]) & ctx.timestamp_mask;
    return static_cast<double>(delta) * ctx.limits.timestampPeriod * 1e-6;
}

// Copies the target out. The render pass left the image in TRANSFER_SRC_OPTIMAL and its
// outgoing dependency orders the colour writes before this copy.
std::vector<float> copy_out(PreparedDraw& p) {
    Scope& scope = p.scope;
    Context& ctx = scope.ctx();
    const VkFormat format = p.target.format;
    const uint32_t channels =
        format == VK_FORMAT_R32G32B32A32_SFLOAT ? 4 : pass_format_channels(format);
    if (channels == 0)
        throw DeviceError(fmt::format("cannot read back VkFormat {}", static_cast<int>(format)));
    const size_t floats = size_t{p.target.width} * p.target.height * channels;
    Buffer readback =
        create_buffer(scope, floats * sizeof(float), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    VkCommandBuffer copy = allocate_command_buffer(scope);
    begin_commands(copy, true);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {p.target.width, p.target.height, 1};
    vkCmdCopyImageToBuffer(copy, p.image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           readback.buffer, 1, &region);
    // Make the copy's writes visible to the host's read of the mapping.
    VkBufferMemoryBarrier to_host{};
    to_host.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
    to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    to_host.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_host.buffer = readback.buffer;
    to_host.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(copy, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0,
                         nullptr, 1, &to_host, 0, nullptr);
    check(vkEndCommandBuffer(copy), "vkEndCommandBuffer");
    submit_and_wait(ctx, copy, p.fence);
    // Copy rows come out in image order: row 0 is framebuffer y = 0, the top.
    std::vector<float> texels(floats);
    read_buffer(ctx, readback, texels.data(), floats * sizeof(float));
    return texels;
}

} // namespace

std::unique_ptr<OffscreenDraw>
OffscreenDraw::create(HeadlessDevice& device, const VariantPipeline& pipeline,
                      const DrawTarget& target, const DrawBindings& bindings,
                      const DrawGeometry& geometry, std::string* error) {
    Context& ctx = *device.context_;
    std::unique_ptr<PreparedDraw> p;
    const bool ok = guarded(ctx, error, [&] {
        p = std::make_unique<PreparedDraw>(ctx);
        p->target = target;
        prepare(*p, pipeline, bindings, geometry);
    });
    if (!ok) return nullptr;
    return std::unique_ptr<OffscreenDraw>(new OffscreenDraw(std::move(p)));
}

OffscreenDraw::OffscreenDraw(std::unique_ptr<PreparedDraw> prepared)
    : prepared_(std::move(prepared)) {}
OffscreenDraw::~OffscreenDraw() = default;

bool OffscreenDraw::submit(double* ms, std::string* error) {
    PreparedDraw& p = *prepared_;
    return guarded(p.scope.ctx(), error, [&] {
        if (ms)
            *ms = timed_submit(p);
        else
            submit_and_wait(p.scope.ctx(), p.draw, p.fence);
    });
}

std::optional<std::vector<float>> OffscreenDraw::read_back(std::string* error) {
    std::vector<float> texels;
    if (!guarded(prepared_->scope.ctx(), error, [&] { texels = copy_out(*prepared_); }))
        return std::nullopt;
    return texels;
}

} // namespace watergen
