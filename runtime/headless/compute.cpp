// HeadlessDevice::compute (compute_job.h): the pipeline of the job's compute stage, its
// descriptors written from the job, one dispatch, every storage buffer read back.
#include "descriptors.h"

#include <fmt/format.h>

namespace watergen {

using namespace headless_detail;

namespace {

void dispatch(Context& ctx, const ComputeJob& job, ComputeOutput& result) {
    const uint32_t groups[3] = {job.group_count_x, job.group_count_y, job.group_count_z};
    for (int i = 0; i < 3; ++i)
        if (groups[i] == 0 || groups[i] > ctx.limits.maxComputeWorkGroupCount[i])
            throw DeviceError(fmt::format("group count {} = {} is outside 1..{}", "xyz"[i],
                                          groups[i], ctx.limits.maxComputeWorkGroupCount[i]));
    // A compute job's layout has no push-constant range: refused here rather than a dispatch
    // that reads bytes nobody pushed.
    if (job.reflection.push_constant)
        throw DeviceError(fmt::format("push-constant block '{}': a compute job binds its uniforms "
                                      "as a uniform buffer only",
                                      job.reflection.push_constant->name));
    Scope scope(ctx);

    DescriptorInputs inputs;
    inputs.sole_uniforms = &job.uniforms;
    inputs.textures = &job.textures;
    inputs.filter = job.filter;
    inputs.storage = &job.buffers;
    inputs.storage_sizes = &job.output_sizes;
    const SetBindings bindings = stage_bindings(job.reflection);
    const std::vector<VkDescriptorSetLayout> layouts =
        create_set_layouts(scope, bindings, VK_SHADER_STAGE_COMPUTE_BIT);
    const BoundDescriptors descriptors = bind_descriptors(scope, layouts, bindings, inputs);
    VkPipelineLayout layout = create_pipeline_layout(scope, layouts);

    VkComputePipelineCreateInfo cci{};
    cci.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    cci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    cci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    cci.stage.module = create_shader_module(scope, job.spirv, "compute");
    cci.stage.pName =
        job.reflection.entry_point.empty() ? "main" : job.reflection.entry_point.c_str();
    const Specialization specialization(job.specialization);
    cci.stage.pSpecializationInfo = specialization.info();
    cci.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    const auto start_pipeline = Clock::now();
    VkResult r = vkCreateComputePipelines(ctx.device, VK_NULL_HANDLE, 1, &cci, nullptr, &pipeline);
    result.pipeline_ms = ms_since(start_pipeline);
    check(r, "vkCreateComputePipelines");
    VkDevice device = ctx.device;
    scope.defer([device, pipeline] { vkDestroyPipeline(device, pipeline, nullptr); });

    VkCommandBuffer cmd = allocate_command_buffer(scope);
    begin_commands(cmd, true);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    if (!descriptors.sets.empty())
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0,
                                static_cast<uint32_t>(descriptors.sets.size()),
                                descriptors.sets.data(), 0, nullptr);
    vkCmdDispatch(cmd, groups[0], groups[1], groups[2]);
    // The shader's storage writes must be visible to the host reading the mappings.
    VkMemoryBarrier to_host{};
    to_host.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    to_host.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0,
                         1, &to_host, 0, nullptr, 0, nullptr);
    check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");

    const auto start = Clock::now();
    submit_and_wait(ctx, cmd, create_fence(scope));
    result.dispatch_ms = ms_since(start);

    for (const auto& [name, buffer] : descriptors.storage_buffers) {
        std::vector<uint8_t> bytes(buffer.size);
        read_buffer(ctx, buffer, bytes.data(), bytes.size());
        result.buffers.emplace(name, std::move(bytes));
    }
}

} // namespace

std::optional<ComputeOutput> HeadlessDevice::compute(const ComputeJob& job, std::string* error) {
    ComputeOutput out;
    if (!guarded(*context_, error, [&] { dispatch(*context_, job, out); })) return std::nullopt;
    return out;
}

} // namespace watergen
