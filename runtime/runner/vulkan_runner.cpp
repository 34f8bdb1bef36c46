// The public VulkanRunner: a layer over the headless device. Every job's failure becomes its
// result's error string, prefixed by what failed; whatever the runner's own code might throw
// (std::bad_alloc) too.
#include "render_jobs.h"

#include <fmt/format.h>

namespace watergen {

namespace {

// Runs one job body (false and `error` on failure); a failed job's partial outputs are cleared.
template <typename Result, typename Body> Result run_job(const char* what, Body&& body) {
    Result result;
    std::string error;
    try {
        if (body(result, &error)) {
            result.ok = true;
            return result;
        }
    } catch (const std::exception& e) {
        error = e.what();
    } catch (...) {
        error = "unknown failure";
    }
    Result failed;
    failed.error = fmt::format("{}: {}", what, error);
    return failed;
}

} // namespace

std::unique_ptr<VulkanRunner> VulkanRunner::create(const DeviceOptions& options,
                                                   std::string* error) {
    auto device = HeadlessDevice::create(options, error);
    if (!device) return nullptr;
    return std::unique_ptr<VulkanRunner>(new VulkanRunner(std::move(device)));
}

VulkanRunner::VulkanRunner(std::unique_ptr<HeadlessDevice> device) : device_(std::move(device)) {}
VulkanRunner::~VulkanRunner() = default;

RenderResult VulkanRunner::render(const RenderJob& job) {
    return run_job<RenderResult>("render", [&](RenderResult& r, std::string* error) {
        return runner_detail::render_job(*device_, job, r, error);
    });
}

std::vector<RenderResult> VulkanRunner::render_interleaved(const std::vector<RenderJob>& jobs,
                                                           uint32_t rounds) {
    std::vector<RenderResult> results;
    const RenderResult all =
        run_job<RenderResult>("render", [&](RenderResult&, std::string* error) {
            return runner_detail::render_jobs_interleaved(*device_, jobs, rounds, results, error);
        });
    if (!all.ok) results.assign(jobs.size(), all);
    return results;
}

ComputeResult VulkanRunner::run_compute(const ComputeJob& job) {
    return run_job<ComputeResult>("compute", [&](ComputeResult& r, std::string* error) {
        auto out = device_->compute(job, error);
        if (out) static_cast<ComputeOutput&>(r) = std::move(*out);
        return out.has_value();
    });
}

} // namespace watergen
