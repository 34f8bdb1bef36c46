// The runner's render jobs (render_jobs.cpp), for VulkanRunner (vulkan_runner.cpp). Private to
// watergen_runner. Nothing here throws on its own account: a failure returns false with
// `error` set (the device's message, or the job's fault).
#pragma once

#include "watergen/runner/vulkan_runner.h"

#include <string>
#include <vector>

namespace watergen::runner_detail {

// The job's pipeline made, drawn once (the JIT), job.timed_draws times timed, counted under
// callgrind when asked, read back into `result`.
bool render_job(HeadlessDevice& device, const RenderJob& job, RenderResult& result,
                std::string* error);

// VulkanRunner::render_interleaved; `results` in job order.
bool render_jobs_interleaved(HeadlessDevice& device, const std::vector<RenderJob>& jobs,
                             uint32_t rounds, std::vector<RenderResult>& results,
                             std::string* error);

} // namespace watergen::runner_detail
