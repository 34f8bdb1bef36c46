// Headless Vulkan runner: renders generated shader variants offscreen and runs compute
// "numeric harness" shaders, on lavapipe by default, for tests and benchmarks.
//
// Errors are data: no call here throws or aborts. A failed job returns ok == false and an
// error string naming the Vulkan call and its VkResult (or the binding the job forgot).
// One runner renders many jobs; every job builds and destroys its own pipeline and
// resources, so results never depend on the order jobs ran in. A runner is not
// thread-safe: use one per thread.
#pragma once

#include "watergen/runtime/reflection.h"

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace watergen {

struct RunnerOptions {
    // Substring of the device name to use instead of lavapipe. Empty: the environment
    // variable WATERGEN_VK_DEVICE if set, else the first llvmpipe / CPU device.
    std::string device;
    // Enable VK_LAYER_KHRONOS_validation + VK_EXT_debug_utils when the layer is installed.
    bool validation = true;
};

struct DeviceInfo {
    std::string name;            // VkPhysicalDeviceProperties::deviceName
    std::string driver_name;     // VkPhysicalDeviceDriverProperties::driverName ("llvmpipe")
    std::string driver_info;     // e.g. "Mesa 22.3.6 (LLVM 15.0.6)"
    uint32_t driver_version = 0; // raw, vendor-specific encoding
    uint32_t api_version = 0;    // VK_MAKE_API_VERSION encoding
    bool validation_enabled = false;
    // 16-bit shader features, enabled on the device whenever it supports them (so a shader
    // may use float16_t / int16_t arithmetic and 16-bit storage-buffer members).
    bool shader_float16 = false;            // VkPhysicalDeviceShaderFloat16Int8Features
    bool shader_int16 = false;              // VkPhysicalDeviceFeatures::shaderInt16
    bool storage_buffer_16bit = false;      // VkPhysicalDevice16BitStorageFeatures
    bool uniform_storage_16bit = false;     // ... uniformAndStorageBuffer16BitAccess
    bool float16_denorms_preserved = false; // FloatControls shaderDenormPreserveFloat16
};

// "1.3.230" from a VK_MAKE_API_VERSION value.
std::string format_api_version(uint32_t version);

enum class TextureFilter { Nearest, Linear };

// RGBA32F texels, layer-major, then rows, then columns: rgba.size() == width*height*layers*4.
// Row 0 is v = 0. Cube layers are in Vulkan face order +X, -X, +Y, -Y, +Z, -Z.
struct TextureData {
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t layers = 1; // 1 = 2D, 6 = cube
    std::vector<float> rgba;
};

// An indexed triangle (or point) list (vulkan_mesh.cpp): one interleaved float vertex buffer,
// attribute i at location i with attribute_sizes[i] floats (1..4), and 32-bit indices. No depth
// buffer: later triangles overwrite earlier ones, so order them back to front.
struct MeshData {
    std::vector<float> vertices;
    std::vector<uint32_t> attribute_sizes;
    std::vector<uint32_t> indices;
    bool points = false; // the indices name points (a point list), not triangles
    bool empty() const { return indices.empty(); }
};

struct RenderJob {
    std::vector<uint32_t> vertex_spirv;
    std::vector<uint32_t> fragment_spirv;
    Reflection vertex_reflection; // descriptor layout = union of both stages' bindings
    Reflection fragment_reflection;
    uint32_t width = 256;
    uint32_t height = 256;
    // Bytes of the one UniformBuffer binding, laid out by the caller from reflection offsets.
    // Must be at least the block's reflected block_size.
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
};

struct RenderResult {
    bool ok = false;
    std::string error;
    uint32_t width = 0;
    uint32_t height = 0;
    // RGBA32F, width*height*4 floats; row 0 is the top of the image (framebuffer y = 0).
    std::vector<float> rgba;
    double pipeline_ms = 0; // CPU time of vkCreateGraphicsPipelines
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

struct ComputeJob {
    std::vector<uint32_t> spirv;
    Reflection reflection;
    // Initial contents of StorageBuffer bindings, by reflection binding name (the block
    // type name, e.g. "Inputs"). Entries no binding uses are ignored.
    std::map<std::string, std::vector<uint8_t>> buffers;
    // Sizes of StorageBuffer bindings the shader only writes (zero-filled before the
    // dispatch). A storage binding in neither map gets its reflected block_size, if nonzero.
    std::map<std::string, uint64_t> output_sizes;
    // Bytes of the UniformBuffer binding, if the shader has one.
    std::vector<uint8_t> uniforms;
    // Float specialization constants by constant_id, as in RenderJob.
    std::map<uint32_t, float> specialization;
    // SampledImage / CombinedImageSampler bindings and their sampler, as in RenderJob.
    std::map<std::string, TextureData> textures;
    TextureFilter filter = TextureFilter::Linear;
    uint32_t group_count_x = 1;
    uint32_t group_count_y = 1;
    uint32_t group_count_z = 1;
};

struct ComputeResult {
    bool ok = false;
    std::string error;
    // Contents of every StorageBuffer binding after the dispatch, by binding name.
    std::map<std::string, std::vector<uint8_t>> buffers;
    double pipeline_ms = 0; // CPU time of vkCreateComputePipelines
    double dispatch_ms = 0; // CPU wall time of the submit + wait (includes JIT)
};

namespace vk_detail {
struct Context;
}

class VulkanRunner {
  public:
    // nullptr and `error` set when no usable device is found or Vulkan fails to start.
    static std::unique_ptr<VulkanRunner> create(const RunnerOptions& options, std::string* error);
    ~VulkanRunner();
    VulkanRunner(const VulkanRunner&) = delete;
    VulkanRunner& operator=(const VulkanRunner&) = delete;

    const DeviceInfo& device_info() const;

    // Every validation-layer warning and error since creation (or the last clear), as
    // "[severity] id: message". Tests fail on any.
    std::vector<std::string> validation_messages() const;
    void clear_validation_messages();

    RenderResult render(const RenderJob& job);
    // Several jobs timed side by side: every pipeline is created and drawn once (untimed, the
    // JIT), then `rounds` rounds each draw job 0, 1, 2, ... in turn, job.timed_draws times
    // (at least once), so that the machine's slow and fast spells fall on every job alike;
    // draw_ms holds the samples in round order. Results are in job order; one failure fails
    // every job (each result's error says what).
    std::vector<RenderResult> render_interleaved(const std::vector<RenderJob>& jobs,
                                                 uint32_t rounds);
    ComputeResult run_compute(const ComputeJob& job);

  private:
    explicit VulkanRunner(std::unique_ptr<vk_detail::Context> context);
    std::unique_ptr<vk_detail::Context> context_;
};

} // namespace watergen
