// The public VulkanRunner: the API boundary where internal RunnerErrors (and anything
// else thrown, e.g. std::bad_alloc) become error strings.
#include "vulkan_internal.h"

#include <fmt/format.h>

namespace watergen {

using vk_detail::Context;

std::unique_ptr<VulkanRunner> VulkanRunner::create(const RunnerOptions& options,
                                                   std::string* error) {
    try {
        return std::unique_ptr<VulkanRunner>(new VulkanRunner(vk_detail::create_context(options)));
    } catch (const std::exception& e) {
        if (error) *error = e.what();
    } catch (...) {
        if (error) *error = "unknown failure while creating the Vulkan runner";
    }
    return nullptr;
}

VulkanRunner::VulkanRunner(std::unique_ptr<Context> context) : context_(std::move(context)) {}
VulkanRunner::~VulkanRunner() = default;

const DeviceInfo& VulkanRunner::device_info() const {
    return context_->info;
}

std::vector<std::string> VulkanRunner::validation_messages() const {
    std::lock_guard<std::mutex> lock(context_->messages_mutex);
    return context_->messages;
}

void VulkanRunner::clear_validation_messages() {
    std::lock_guard<std::mutex> lock(context_->messages_mutex);
    context_->messages.clear();
}

namespace {

// Runs one job body; on failure clears partial outputs and records the error.
template <typename Result, typename Body>
Result guarded(Context& ctx, const char* what, Body&& body) {
    Result result;
    try {
        if (ctx.unusable)
            throw vk_detail::RunnerError(
                "the Vulkan device is unusable after an earlier timeout or device loss");
        body(result);
        result.ok = true;
    } catch (const std::exception& e) {
        result = Result{};
        result.error = fmt::format("{}: {}", what, e.what());
    } catch (...) {
        result = Result{};
        result.error = fmt::format("{}: unknown failure", what);
    }
    return result;
}

} // namespace

RenderResult VulkanRunner::render(const RenderJob& job) {
    return guarded<RenderResult>(
        *context_, "render", [&](RenderResult& r) { vk_detail::render_job(*context_, job, r); });
}

std::vector<RenderResult> VulkanRunner::render_interleaved(const std::vector<RenderJob>& jobs,
                                                           uint32_t rounds) {
    std::vector<RenderResult> results;
    const RenderResult all = guarded<RenderResult>(*context_, "render", [&](RenderResult&) {
        vk_detail::render_jobs_interleaved(*context_, jobs, rounds, results);
    });
    if (!all.ok) results.assign(jobs.size(), all);
    return results;
}

ComputeResult VulkanRunner::run_compute(const ComputeJob& job) {
    return guarded<ComputeResult>(
        *context_, "compute", [&](ComputeResult& r) { vk_detail::compute_job(*context_, job, r); });
}

} // namespace watergen
