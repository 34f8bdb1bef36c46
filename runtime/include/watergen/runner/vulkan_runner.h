// The test runner on watergen's headless device (watergen/headless/headless_device.h): renders
// generated shader variants offscreen, timed (GPU timestamps, interleaved rounds, counted draws
// under callgrind), and runs compute "numeric harness" shaders, on lavapipe by default, for the
// tests, the tools (watergen render, cost, compare, caustics, probe, bench) and the benches.
//
// Errors are data: no call here throws or aborts. A failed job returns ok == false and an
// error string naming the Vulkan call and its VkResult (or the binding the job forgot).
// One runner renders many jobs; every job builds and destroys its own pipeline and
// resources, so results never depend on the order jobs ran in. A runner is not
// thread-safe: use one per thread.
#pragma once

#include "watergen/headless/compute_job.h"
#include "watergen/headless/headless_device.h"
#include "watergen/headless/texture_data.h"
#include "watergen/runtime/reflection.h"

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace watergen {

// An indexed triangle (or point, or patch) list: one interleaved float vertex buffer,
// attribute i at location i with attribute_sizes[i] floats (1..4), and 32-bit indices. No depth
// buffer: later triangles overwrite earlier ones, so order them back to front.
struct MeshData {
    std::vector<float> vertices;
    std::vector<uint32_t> attribute_sizes;
    std::vector<uint32_t> indices;
    bool points = false; // the indices name points (a point list), not triangles
    // > 0: the indices name patches of this many control points, drawn through the job's
    // tessellation stages (which need them).
    uint32_t patch_control_points = 0;
    bool empty() const { return indices.empty(); }
};

struct RenderJob {
    std::vector<uint32_t> vertex_spirv;
    std::vector<uint32_t> fragment_spirv;
    Reflection vertex_reflection; // descriptor layout = union of both stages' bindings
    Reflection fragment_reflection;
    // Tessellation control and evaluation stages, both or neither (empty SPIR-V): then `mesh`
    // holds patches (MeshData::patch_control_points) and the device must have the
    // tessellationShader feature (DeviceInfo::tessellation_shader). Their bindings join the
    // union; `uniforms` fills the block all stages share.
    std::vector<uint32_t> tess_control_spirv;
    std::vector<uint32_t> tess_evaluation_spirv;
    Reflection tess_control_reflection;
    Reflection tess_evaluation_reflection;
    uint32_t width = 256;
    uint32_t height = 256;
    // Bytes of the one UniformBuffer binding, or of the push-constant block (a stage's
    // Reflection::push_constant: pushed with vkCmdPushConstants, its block_size rounded up to
    // 4), laid out by the caller from reflection offsets. Must be at least the block's
    // reflected block_size. Shaders with both a uniform binding and a push-constant block fail.
    std::vector<uint8_t> uniforms;
    // Values of float specialization constants by constant_id (reflection's
    // specialization_constants), given to both stages at pipeline creation. A constant with no
    // entry keeps the module's default; an id neither module declares is ignored.
    std::map<uint32_t, float> specialization;
    // SampledImage / CombinedImageSampler bindings, by reflection binding name. A binding
    // with no entry fails the job (naming the binding); entries no binding uses are
    // ignored, so one set of inputs can serve many variants.
    std::map<std::string, TextureData> textures;
    // Used for every Sampler / CombinedImageSampler binding; clamp to edge, no mips.
    TextureFilter filter = TextureFilter::Linear;
    // Draws after the first one, each timed with GPU timestamp queries.
    uint32_t timed_draws = 5;
    // Under valgrind's callgrind tool (valgrind --tool=callgrind --instr-atstart=no): two counts
    // (draw_count.h reads them). "<label> first": pipeline creation through the first draw,
    // which is when lavapipe JIT-compiles the shaders; "<label>": one more draw after the timed
    // ones, the steady draw's work alone. Ignored elsewhere and when empty.
    std::string counted_draw_label;
    // false: only the steady draw is counted (callgrind runs the JIT about twice as fast with
    // instrumentation off).
    bool count_first_draw = true;
    // Geometry is a fullscreen triangle: no vertex buffers, 3 vertices, the vertex shader
    // derives positions from gl_VertexIndex. Unless `mesh` is non-empty: then it is drawn
    // indexed, from its vertex buffer.
    MeshData mesh;
    // Blend ONE + ONE into the target cleared to 0, so overlapping triangles add up (the
    // caustics pass accumulates light this way); false: each fragment replaces the pixel.
    bool additive_blend = false;
    // Cull back faces (front faces counter-clockwise in the framebuffer): which way a mesh's
    // triangles wind, seen on the device; false: no culling.
    bool cull_back_faces = false;
    // RGBA32F, width x height x 4, row 0 at the top: what lies under the water (the scene an
    // engine drew before it). A pixel no fragment wrote (alpha 0) takes its rgb and keeps alpha
    // 0 in RenderResult::rgba. Empty: the cleared target (0) stays.
    std::vector<float> background;
};

struct RenderResult {
    bool ok = false;
    std::string error;
    uint32_t width = 0;
    uint32_t height = 0;
    // RGBA32F, width*height*4 floats; row 0 is the top of the image (framebuffer y = 0).
    std::vector<float> rgba;
    // CPU time of the pipeline's creation (VariantPipeline::create: its descriptor set layouts,
    // shader modules and vkCreateGraphicsPipelines).
    double pipeline_ms = 0;
    // CPU wall time of the first submit + wait. Includes lavapipe's LLVM JIT, unless
    // Mesa's own on-disk shader cache already holds the shader (MESA_SHADER_CACHE_DIR);
    // MESA_SHADER_CACHE_DISABLE=true makes this independent of earlier runs.
    double first_draw_ms = 0;
    double steady_draw_ms = 0; // median of draw_ms (0 when timed_draws == 0)
    // One sample per timed draw: GPU timestamps (top of pipe before the render pass to
    // bottom of pipe after it, scaled by timestampPeriod); CPU wall time of submit + wait
    // only if the queue cannot write timestamps.
    std::vector<double> draw_ms;
};

struct ComputeResult : ComputeOutput {
    bool ok = false;
    std::string error;
};

class VulkanRunner {
  public:
    // nullptr and `error` when no usable device is found or Vulkan fails to start.
    static std::unique_ptr<VulkanRunner> create(const DeviceOptions& options, std::string* error);
    ~VulkanRunner();
    VulkanRunner(const VulkanRunner&) = delete;
    VulkanRunner& operator=(const VulkanRunner&) = delete;

    // The device every job runs on.
    HeadlessDevice& device() { return *device_; }
    const DeviceInfo& device_info() const { return device_->info(); }

    // Every validation-layer warning and error since creation (or the last clear), as
    // "[severity] id: message". Tests fail on any.
    std::vector<std::string> validation_messages() const { return device_->validation_messages(); }
    void clear_validation_messages() { device_->clear_validation_messages(); }

    RenderResult render(const RenderJob& job);
    // Several jobs timed side by side: every pipeline is created and drawn once (untimed, the
    // JIT), then `rounds` rounds each draw job 0, 1, 2, ... in turn, job.timed_draws times
    // (at least once), so that the machine's slow and fast spells fall on every job alike;
    // draw_ms holds the samples in round order. Results are in job order; one failure fails
    // every job (each result's error says what).
    std::vector<RenderResult> render_interleaved(const std::vector<RenderJob>& jobs,
                                                 uint32_t rounds);
    // HeadlessDevice::compute, its error prefixed "compute: ".
    ComputeResult run_compute(const ComputeJob& job);

  private:
    explicit VulkanRunner(std::unique_ptr<HeadlessDevice> device);
    std::unique_ptr<HeadlessDevice> device_;
};

} // namespace watergen
