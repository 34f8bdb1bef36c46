// Render jobs: offscreen RGBA32F target, fullscreen-triangle graphics pipeline, one
// untimed first draw (lavapipe JITs the shaders there), timestamp-timed steady draws,
// readback.
#include "pipeline_state.h"
#include "vulkan_internal.h"
#include "vulkan_mesh.h"

#include <fmt/format.h>

#include <algorithm>

#include <valgrind/callgrind.h>

namespace watergen::vk_detail {
namespace {

constexpr uint32_t kMaxTimedDraws = 1000;

VkRenderPass create_render_pass(Scope& scope) {
    VkRenderPass pass = VK_NULL_HANDLE;
    VkDevice device = scope.ctx().device;
    vk_check(vk_state::create_offscreen_render_pass(device, &pass), "vkCreateRenderPass");
    scope.defer([device, pass] { vkDestroyRenderPass(device, pass, nullptr); });
    return pass;
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
    vk_check(vkCreateFramebuffer(device, &fci, nullptr, &fb), "vkCreateFramebuffer");
    scope.defer([device, fb] { vkDestroyFramebuffer(device, fb, nullptr); });
    return fb;
}

const char* entry_point(const Reflection& r) {
    return r.entry_point.empty() ? "main" : r.entry_point.c_str();
}

struct Pipeline {
    VkPipeline pipeline = VK_NULL_HANDLE;
    double create_ms = 0;
};

Pipeline create_pipeline(Scope& scope, const RenderJob& job, VkPipelineLayout layout,
                         VkRenderPass pass) {
    VkPipelineShaderStageCreateInfo stages[2]{};
    stages[0].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = create_shader_module(scope, job.vertex_spirv, "vertex");
    stages[0].pName = entry_point(job.vertex_reflection);
    stages[1].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = create_shader_module(scope, job.fragment_spirv, "fragment");
    stages[1].pName = entry_point(job.fragment_reflection);
    const Specialization specialization(job.specialization);
    stages[0].pSpecializationInfo = specialization.info();
    stages[1].pSpecializationInfo = specialization.info();

    // Fullscreen triangle: positions come from gl_VertexIndex, so no vertex input. An
    // indexed grid mesh (job.mesh) adds its binding/attributes here.
    const vk_state::VertexInput vertex_input(mesh_attribute_sizes(job.mesh));
    vk_state::FixedFunction fixed;
    if (job.mesh.points) fixed.points();
    if (job.additive_blend) {
        if (!vk_state::blendable(scope.ctx().physical, VK_FORMAT_R32G32B32A32_SFLOAT))
            throw RunnerError(fmt::format("device '{}' cannot blend into "
                                          "VK_FORMAT_R32G32B32A32_SFLOAT (additive_blend)",
                                          scope.ctx().info.name));
        fixed.additive_blend();
    }

    VkViewport viewport{0.0f, 0.0f, static_cast<float>(job.width), static_cast<float>(job.height),
                        0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, {job.width, job.height}};
    VkPipelineViewportStateCreateInfo viewport_state{};
    viewport_state.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
    viewport_state.viewportCount = 1;
    viewport_state.pViewports = &viewport;
    viewport_state.scissorCount = 1;
    viewport_state.pScissors = &scissor;

    VkGraphicsPipelineCreateInfo gci{};
    fixed.apply(gci);
    gci.stageCount = 2;
    gci.pStages = stages;
    gci.pVertexInputState = &vertex_input.info;
    gci.pViewportState = &viewport_state;
    gci.layout = layout;
    gci.renderPass = pass;
    gci.subpass = 0;

    Pipeline p;
    VkDevice device = scope.ctx().device;
    // No VkPipelineCache: every job pays full creation cost, so timings and results do
    // not depend on which jobs ran before.
    const auto start = Clock::now();
    VkResult r = vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &gci, nullptr, &p.pipeline);
    p.create_ms = ms_since(start);
    vk_check(r, "vkCreateGraphicsPipelines");
    VkPipeline pipeline = p.pipeline;
    scope.defer([device, pipeline] { vkDestroyPipeline(device, pipeline, nullptr); });
    return p;
}

VkQueryPool create_timestamp_pool(Scope& scope) {
    VkQueryPoolCreateInfo qci{};
    qci.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
    qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qci.queryCount = 2;
    VkQueryPool pool = VK_NULL_HANDLE;
    VkDevice device = scope.ctx().device;
    vk_check(vkCreateQueryPool(device, &qci, nullptr, &pool), "vkCreateQueryPool");
    scope.defer([device, pool] { vkDestroyQueryPool(device, pool, nullptr); });
    return pool;
}

void begin_reusable(VkCommandBuffer cmd) {
    VkCommandBufferBeginInfo bi{};
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    // No ONE_TIME_SUBMIT: the draw command buffer is submitted once per draw.
    vk_check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
}

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// What one draw of a job binds.
struct DrawState {
    VkRenderPass pass = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    const BoundDescriptors* descriptors = nullptr;
    const MeshBuffers* mesh = nullptr;
    VkQueryPool queries = VK_NULL_HANDLE; // null without timestamp support
};

// One recorded command buffer, resubmitted for the first and every timed draw.
VkCommandBuffer record_draw(Scope& scope, const RenderJob& job, const DrawState& d) {
    VkCommandBuffer draw = allocate_command_buffer(scope);
    begin_reusable(draw);
    if (d.queries) {
        vkCmdResetQueryPool(draw, d.queries, 0, 2);
        vkCmdWriteTimestamp(draw, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, d.queries, 0);
    }
    VkClearValue clear{};
    VkRenderPassBeginInfo rbi{};
    rbi.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    rbi.renderPass = d.pass;
    rbi.framebuffer = d.framebuffer;
    rbi.renderArea = {{0, 0}, {job.width, job.height}};
    rbi.clearValueCount = 1;
    rbi.pClearValues = &clear;
    vkCmdBeginRenderPass(draw, &rbi, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(draw, VK_PIPELINE_BIND_POINT_GRAPHICS, d.pipeline);
    if (!d.descriptors->sets.empty())
        vkCmdBindDescriptorSets(draw, VK_PIPELINE_BIND_POINT_GRAPHICS, d.layout, 0,
                                static_cast<uint32_t>(d.descriptors->sets.size()),
                                d.descriptors->sets.data(), 0, nullptr);
    if (d.mesh->index_count)
        record_mesh_draw(draw, *d.mesh);
    else
        vkCmdDraw(draw, 3, 1, 0, 0);
    vkCmdEndRenderPass(draw);
    // Bottom of pipe: the sample is taken once the draw has fully completed.
    if (d.queries) vkCmdWriteTimestamp(draw, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, d.queries, 1);
    vk_check(vkEndCommandBuffer(draw), "vkEndCommandBuffer");
    return draw;
}

bool counting(const RenderJob& job) {
    return !job.counted_draw_label.empty() && RUNNING_ON_VALGRIND;
}

// One more submit of the recorded draw: its GPU time from the timestamp queries, or the CPU
// wall time of submit + wait where the queue has no timestamps.
double timed_draw(Context& ctx, VkCommandBuffer draw, VkFence fence, VkQueryPool queries) {
    const auto start = Clock::now();
    submit_and_wait(ctx, draw, fence);
    const double wall_ms = ms_since(start);
    if (!queries) return wall_ms;
    uint64_t ticks[2] = {};
    vk_check(vkGetQueryPoolResults(ctx.device, queries, 0, 2, sizeof(ticks), ticks,
                                   sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
             "vkGetQueryPoolResults");
    const uint64_t delta = (ticks[1] - ticks[0]) & ctx.timestamp_mask;
    return static_cast<double>(delta) * ctx.limits.timestampPeriod * 1e-6;
}

// The untimed first draw (lavapipe JIT-compiles the shaders there).
void first_draw(Context& ctx, const RenderJob& job, VkCommandBuffer draw, VkFence fence,
                RenderResult& result) {
    const auto start = Clock::now();
    submit_and_wait(ctx, draw, fence);
    result.first_draw_ms = ms_since(start);
    if (counting(job) && job.count_first_draw) { // switched on in prepare_render
        CALLGRIND_DUMP_STATS_AT((job.counted_draw_label + " first").c_str());
        CALLGRIND_STOP_INSTRUMENTATION;
    }
}

// Submits the draw once, then job.timed_draws times more, timing each.
void run_draws(Context& ctx, const RenderJob& job, VkCommandBuffer draw, VkFence fence,
               VkQueryPool queries, RenderResult& result) {
    first_draw(ctx, job, draw, fence, result);
    for (uint32_t i = 0; i < job.timed_draws; ++i)
        result.draw_ms.push_back(timed_draw(ctx, draw, fence, queries));
    result.steady_draw_ms = median(result.draw_ms);
    if (counting(job)) {
        // Only this draw is instrumented: the count is the draw's work, JIT and setup excluded.
        CALLGRIND_START_INSTRUMENTATION;
        CALLGRIND_ZERO_STATS;
        submit_and_wait(ctx, draw, fence);
        CALLGRIND_DUMP_STATS_AT(job.counted_draw_label.c_str());
        CALLGRIND_STOP_INSTRUMENTATION;
    }
}

// Copies the colour target into result.rgba. The render pass left the image in
// TRANSFER_SRC_OPTIMAL and its outgoing dependency orders the colour writes before this copy.
void read_back(Scope& scope, const RenderJob& job, const Image& target, VkFence fence,
               RenderResult& result) {
    Context& ctx = scope.ctx();
    const VkDeviceSize bytes = VkDeviceSize{job.width} * job.height * 4 * sizeof(float);
    Buffer readback = create_buffer(scope, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    VkCommandBuffer copy = allocate_command_buffer(scope);
    begin_reusable(copy);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {job.width, job.height, 1};
    vkCmdCopyImageToBuffer(copy, target.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
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
    vk_check(vkEndCommandBuffer(copy), "vkEndCommandBuffer");
    submit_and_wait(ctx, copy, fence);

    // Copy rows come out in image order: row 0 is framebuffer y = 0, the top.
    result.rgba.resize(size_t{job.width} * job.height * 4);
    read_buffer(ctx, readback, result.rgba.data(), bytes);
    result.width = job.width;
    result.height = job.height;
}

// One job's target, descriptors, pipeline and recorded draw, alive while it is drawn.
struct PreparedRender {
    explicit PreparedRender(Context& ctx) : scope(ctx) {}
    Scope scope;
    Image target;
    BoundDescriptors descriptors;
    MeshBuffers mesh;
    DrawState state;
    VkCommandBuffer draw = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
};

void prepare_render(PreparedRender& p, const RenderJob& job, RenderResult& result) {
    if (job.timed_draws > kMaxTimedDraws)
        throw RunnerError(
            fmt::format("timed_draws {} exceeds {}", job.timed_draws, kMaxTimedDraws));
    Scope& scope = p.scope;
    p.target = create_color_target(scope, job.width, job.height);
    DescriptorInputs inputs;
    inputs.uniforms = &job.uniforms;
    inputs.textures = &job.textures;
    inputs.filter = job.filter;
    p.descriptors = bind_descriptors(scope,
                                     {{&job.vertex_reflection, VK_SHADER_STAGE_VERTEX_BIT},
                                      {&job.fragment_reflection, VK_SHADER_STAGE_FRAGMENT_BIT}},
                                     inputs);
    DrawState& state = p.state;
    state.descriptors = &p.descriptors;
    state.layout = create_pipeline_layout(scope, p.descriptors);
    state.pass = create_render_pass(scope);
    state.framebuffer = create_framebuffer(scope, state.pass, p.target);
    if (counting(job) && job.count_first_draw) { // pipeline creation and first draw: the JIT
        CALLGRIND_START_INSTRUMENTATION;
        CALLGRIND_ZERO_STATS;
    }
    const Pipeline pipeline = create_pipeline(scope, job, state.layout, state.pass);
    state.pipeline = pipeline.pipeline;
    result.pipeline_ms = pipeline.create_ms;
    p.mesh = upload_mesh(scope, job.mesh); // index_count 0 without a mesh
    state.mesh = &p.mesh;
    if (scope.ctx().timestamp_mask != 0) state.queries = create_timestamp_pool(scope);
    p.draw = record_draw(scope, job, state);
    p.fence = create_fence(scope);
}

} // namespace

void render_job(Context& ctx, const RenderJob& job, RenderResult& result) {
    PreparedRender p(ctx);
    prepare_render(p, job, result);
    run_draws(ctx, job, p.draw, p.fence, p.state.queries, result);
    read_back(p.scope, job, p.target, p.fence, result);
}

void render_jobs_interleaved(Context& ctx, const std::vector<RenderJob>& jobs, uint32_t rounds,
                             std::vector<RenderResult>& results) {
    results.assign(jobs.size(), RenderResult{});
    std::vector<std::unique_ptr<PreparedRender>> prepared;
    for (size_t i = 0; i < jobs.size(); ++i) {
        prepared.push_back(std::make_unique<PreparedRender>(ctx));
        prepare_render(*prepared[i], jobs[i], results[i]);
        first_draw(ctx, jobs[i], prepared[i]->draw, prepared[i]->fence, results[i]);
    }
    // A B C A B C ...: a slow spell of the machine lands on every job alike.
    for (uint32_t r = 0; r < rounds; ++r)
        for (size_t i = 0; i < jobs.size(); ++i)
            for (uint32_t d = 0; d < std::max(jobs[i].timed_draws, 1u); ++d)
                results[i].draw_ms.push_back(timed_draw(ctx, prepared[i]->draw, prepared[i]->fence,
                                                        prepared[i]->state.queries));
    for (size_t i = 0; i < jobs.size(); ++i) {
        results[i].steady_draw_ms = median(results[i].draw_ms);
        read_back(prepared[i]->scope, jobs[i], prepared[i]->target, prepared[i]->fence, results[i]);
        results[i].ok = true;
    }
}

} // namespace watergen::vk_detail
