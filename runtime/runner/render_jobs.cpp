// Render jobs on the headless device: the job's stages made into a VariantPipeline with the
// device's RGBA32F render pass, its draw prepared once (OffscreenDraw), one untimed first draw
// (lavapipe JITs the shaders there), timestamp-timed steady draws, an optional counted draw
// under callgrind, the readback.
#include "render_jobs.h"

#include "watergen/headless/offscreen_draw.h"
#include "watergen/runtime/variant_pipeline.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <optional>

#include <valgrind/callgrind.h>

namespace watergen::runner_detail {
namespace {

constexpr uint32_t kMaxTimedDraws = 1000;

bool fail(std::string* error, std::string message) {
    *error = std::move(message);
    return false;
}

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

bool counting(const RenderJob& job) {
    return !job.counted_draw_label.empty() && RUNNING_ON_VALGRIND;
}

// A job's pipeline and its prepared draw (destroyed first), alive while it is drawn.
struct PreparedJob {
    std::optional<VariantPipeline> pipeline;
    std::unique_ptr<OffscreenDraw> draw;
};

// Creates the pipeline (counted as the start of the first draw under callgrind) and prepares
// the draw: target, descriptors from the job's inputs, the mesh's buffers.
bool prepare(HeadlessDevice& device, const RenderJob& job, PreparedJob& p, RenderResult& result,
             std::string* error) {
    if (job.timed_draws > kMaxTimedDraws)
        return fail(error,
                    fmt::format("timed_draws {} exceeds {}", job.timed_draws, kMaxTimedDraws));
    // 0x07230203 is the SPIR-V magic number; catching a wrong blob here gives a clearer
    // message than the driver would.
    // Tessellation stages are optional, both or neither: one alone is checked as missing.
    const bool tessellated = !job.tess_control_spirv.empty() || !job.tess_evaluation_spirv.empty();
    std::vector<std::pair<const std::vector<uint32_t>*, const char*>> modules = {
        {&job.vertex_spirv, "vertex"}, {&job.fragment_spirv, "fragment"}};
    if (tessellated)
        modules.insert(modules.end(), {{&job.tess_control_spirv, "tess_control"},
                                       {&job.tess_evaluation_spirv, "tess_evaluation"}});
    for (const auto& [spirv, what] : modules)
        if (spirv->size() < 5 || (*spirv)[0] != 0x07230203u)
            return fail(error, fmt::format("{} SPIR-V is empty or not SPIR-V", what));
    if (tessellated && !device.info().tessellation_shader)
        return fail(error, "the job has tessellation stages; the device has no "
                           "tessellationShader feature");
    // Additive blending needs a target format the device blends into: render_pass(format) checks.
    const VkRenderPass pass = job.additive_blend
                                  ? device.render_pass(VK_FORMAT_R32G32B32A32_SFLOAT, error)
                                  : device.render_pass();
    if (!pass) return false;
    // No VkPipelineCache: every job pays full creation cost, so timings and results do not
    // depend on which jobs ran before.
    VariantPipelineDesc desc{&job.vertex_spirv,
                             &job.fragment_spirv,
                             &job.vertex_reflection,
                             &job.fragment_reflection,
                             pass,
                             0,
                             job.specialization,
                             VK_NULL_HANDLE};
    // The device's own limit: a push-constant block past the guaranteed 128 bytes draws where
    // the device pushes it.
    VkPhysicalDeviceProperties props{};
    vkGetPhysicalDeviceProperties(device.physical(), &props);
    desc.max_push_constants_size = props.limits.maxPushConstantsSize;
    if (tessellated) {
        desc.tess_control_spirv = &job.tess_control_spirv;
        desc.tess_evaluation_spirv = &job.tess_evaluation_spirv;
        desc.tess_control_reflection = &job.tess_control_reflection;
        desc.tess_evaluation_reflection = &job.tess_evaluation_reflection;
    }
    PipelineGeometry geometry;
    if (!job.mesh.empty()) geometry.attribute_sizes = job.mesh.attribute_sizes;
    geometry.points = job.mesh.points;
    geometry.patch_control_points = job.mesh.patch_control_points;
    geometry.cull_back_faces = job.cull_back_faces;
    geometry.additive_blend = job.additive_blend;
    const bool count_first = counting(job) && job.count_first_draw;
    if (count_first) { // pipeline creation and the first draw: the JIT
        CALLGRIND_START_INSTRUMENTATION;
        CALLGRIND_ZERO_STATS;
    }
    const auto start = std::chrono::steady_clock::now();
    p.pipeline = VariantPipeline::create(device.device(), desc, geometry, error);
    result.pipeline_ms = ms_since(start);
    if (count_first) CALLGRIND_STOP_INSTRUMENTATION; // not the uploads: first_draw() resumes
    if (!p.pipeline) return false;

    const DrawTarget target{.width = job.width, .height = job.height};
    const DrawBindings bindings{
        .sole_uniforms = &job.uniforms, .textures = &job.textures, .filter = job.filter};
    const DrawGeometry mesh{&job.mesh.vertices,
                            &job.mesh.indices,
                            job.mesh.attribute_sizes,
                            job.mesh.points,
                            "mesh",
                            job.mesh.patch_control_points};
    p.draw = OffscreenDraw::create(device, *p.pipeline, target, bindings, mesh, error);
    return p.draw != nullptr;
}

// The untimed first draw (lavapipe JIT-compiles the shaders there).
bool first_draw(const RenderJob& job, OffscreenDraw& draw, RenderResult& result,
                std::string* error) {
    const bool count_first = counting(job) && job.count_first_draw;
    if (count_first) CALLGRIND_START_INSTRUMENTATION; // zeroed in prepare()
    const auto start = std::chrono::steady_clock::now();
    const bool ok = draw.submit(nullptr, error);
    result.first_draw_ms = ms_since(start);
    if (count_first) {
        CALLGRIND_DUMP_STATS_AT((job.counted_draw_label + " first").c_str());
        CALLGRIND_STOP_INSTRUMENTATION;
    }
    return ok;
}

bool timed_draw(OffscreenDraw& draw, RenderResult& result, std::string* error) {
    double ms = 0;
    if (!draw.submit(&ms, error)) return false;
    result.draw_ms.push_back(ms);
    return true;
}

// One more draw under callgrind when asked: only this draw is instrumented, so the count is the
// draw's work, JIT and setup excluded.
bool counted_draw(const RenderJob& job, OffscreenDraw& draw, std::string* error) {
    if (!counting(job)) return true;
    CALLGRIND_START_INSTRUMENTATION;
    CALLGRIND_ZERO_STATS;
    const bool ok = draw.submit(nullptr, error);
    CALLGRIND_DUMP_STATS_AT(job.counted_draw_label.c_str());
    CALLGRIND_STOP_INSTRUMENTATION;
    return ok;
}

bool read_back(const RenderJob& job, OffscreenDraw& draw, RenderResult& result,
               std::string* error) {
    auto texels = draw.read_back(error);
    if (!texels) return false;
    result.rgba = std::move(*texels);
    if (job.background.size() == result.rgba.size())
        for (size_t p = 0; p < result.rgba.size(); p += 4)
            if (result.rgba[p + 3] == 0.0f)
                for (size_t c = 0; c < 3; ++c)
                    result.rgba[p + c] = job.background[p + c];
    result.width = job.width;
    result.height = job.height;
    return true;
}

} // namespace

bool render_job(HeadlessDevice& device, const RenderJob& job, RenderResult& result,
                std::string* error) {
    PreparedJob p;
    if (!prepare(device, job, p, result, error) || !first_draw(job, *p.draw, result, error))
        return false;
    for (uint32_t i = 0; i < job.timed_draws; ++i)
        if (!timed_draw(*p.draw, result, error)) return false;
    result.steady_draw_ms = median(result.draw_ms);
    return counted_draw(job, *p.draw, error) && read_back(job, *p.draw, result, error);
}

bool render_jobs_interleaved(HeadlessDevice& device, const std::vector<RenderJob>& jobs,
                             uint32_t rounds, std::vector<RenderResult>& results,
                             std::string* error) {
    results.assign(jobs.size(), RenderResult{});
    std::vector<PreparedJob> prepared(jobs.size());
    for (size_t i = 0; i < jobs.size(); ++i)
        if (!prepare(device, jobs[i], prepared[i], results[i], error) ||
            !first_draw(jobs[i], *prepared[i].draw, results[i], error))
            return false;
    // A B C A B C ...: a slow spell of the machine lands on every job alike.
    for (uint32_t r = 0; r < rounds; ++r)
        for (size_t i = 0; i < jobs.size(); ++i)
            for (uint32_t d = 0; d < std::max(jobs[i].timed_draws, 1u); ++d)
                if (!timed_draw(*prepared[i].draw, results[i], error)) return false;
    for (size_t i = 0; i < jobs.size(); ++i) {
        results[i].steady_draw_ms = median(results[i].draw_ms);
        if (!read_back(jobs[i], *prepared[i].draw, results[i], error)) return false;
        results[i].ok = true;
    }
    return true;
}

} // namespace watergen::runner_detail
