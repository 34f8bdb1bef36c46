// watergen's one headless Vulkan device (component watergen::headless), for the tools, the tests,
// the test runner (watergen/runner/vulkan_runner.h) and the example consumer. An engine brings
// its own device and frame and links only watergen::runtime.
//
// Device: DeviceOptions::device, else the environment variable WATERGEN_VK_DEVICE (a substring
// of the device name), else lavapipe, else the first CPU device: results are reproducible. The
// validation layer is enabled when installed and its warnings and errors are collected; the
// 16-bit shader features the device has are enabled. It draws offscreen: a VariantPipeline's
// fullscreen triangle into an RGBA32F image read back (draw()), a build's companion pass into
// its float target read back as the texture the water variant samples (draw_pass()), any draw
// prepared once and submitted as often as wanted (offscreen_draw.h); and it runs compute
// dispatches (compute()).
//
// Errors are data: no call throws or aborts. A failure returns nullptr, nullopt, an empty
// vector or false and sets `*error` to what failed (the Vulkan call and its VkResult, or the
// input at fault). After a wait timed out or the device was lost, every later call fails saying
// so. Not thread-safe: one device per thread.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "watergen/headless/compute_job.h"
#include "watergen/headless/texture_data.h"
#include "watergen/runtime/build_pass.h"
#include "watergen/runtime/variant_pipeline.h"

namespace watergen {

struct DeviceOptions {
    // Substring of the device name to use instead of lavapipe. Empty: the environment
    // variable WATERGEN_VK_DEVICE if set, else lavapipe, else the first CPU device.
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
    // VkPhysicalDeviceFeatures::tessellationShader, enabled whenever supported (the
    // tessellated mesh path), with the device's maxTessellationGenerationLevel (0 without).
    bool tessellation_shader = false;
    uint32_t max_tessellation_level = 0;
};

// "1.3.230" from a VK_MAKE_API_VERSION value.
std::string format_api_version(uint32_t version);

// What draw() binds.
struct HeadlessDraw {
    uint32_t width = 256, height = 256;
    // Bytes of each uniform buffer binding, or of the push-constant block, by block name
    // (UniformWriter::pack()).
    std::map<std::string, std::vector<uint8_t>> uniforms;
    // Images of the sampled-image bindings, by binding name; every sampler is clamp to edge
    // with `filter`.
    std::map<std::string, TextureData> textures;
    TextureFilter filter = TextureFilter::Linear;
    // A mesh variant's grid (water_grid(): interleaved floats, attribute_sizes per location,
    // triangles or patches of patch_control_points), drawn indexed in its order; none: the
    // fullscreen triangle. The pipeline's PipelineGeometry must say the same.
    const std::vector<float>* vertices = nullptr;
    const std::vector<uint32_t>* indices = nullptr;
    std::vector<uint32_t> attribute_sizes = {};
    uint32_t patch_control_points = 0;
};

namespace headless_detail {
struct Context;
}

class HeadlessDevice {
  public:
    // nullptr and `error` when no device fits or Vulkan fails to start (with what the loader
    // said about the drivers it could not load).
    static std::unique_ptr<HeadlessDevice> create(const DeviceOptions& options, std::string* error);
    ~HeadlessDevice();
    HeadlessDevice(const HeadlessDevice&) = delete;
    HeadlessDevice& operator=(const HeadlessDevice&) = delete;

    VkPhysicalDevice physical() const;
    VkDevice device() const;
    const DeviceInfo& info() const;
    const std::string& device_name() const { return info().name; }

    // Every validation-layer warning and error since creation (or the last clear), as
    // "[severity] id: message". Tests fail on any.
    std::vector<std::string> validation_messages() const;
    void clear_validation_messages();

    // One RGBA32F colour attachment, cleared, left ready to be copied out: the water's target.
    VkRenderPass render_pass() const;
    // The same with one colour attachment of `format` (a companion pass's target, pass_format()),
    // made on first use and kept. Null and `error` when the device cannot blend into the format
    // (a pass adds its fragments) or Vulkan fails.
    VkRenderPass render_pass(VkFormat format, std::string* error);

    // Draws the pipeline (made with render_pass()) once, its fullscreen triangle; RGBA32F pixels,
    // row 0 at the top. Empty and `error` when a binding has no input or a Vulkan call fails.
    std::vector<float> draw(const VariantPipeline& pipeline, const HeadlessDraw& inputs,
                            std::string* error);

    // Draws a companion pass: `pipeline` from create_pass_pipeline(draw, ...) with
    // render_pass(pass_format(draw)), over `grid` (pass_grid(draw, ...): its vertices and
    // indices, drawn indexed in their order), with `uniforms` by block name (the pass's block
    // packed by UniformWriter against its vertex reflection), into a grid.texels square target
    // cleared to draw.clear. Returns the target as a texture ready to bind as the water
    // variant's caustics_map: draw.channel in r, g and b, a = 1 (as watergen render feeds it),
    // row 0 at the top (texel row j is z = z0 + (j + 0.5) size / texels). nullopt and `error`
    // for a grid that does not fit the draw (texels, a vertex count beyond 2^26 or the device's
    // image size, indices past the vertices or not whole triangles), a uniform block the
    // pipeline does not have or of the wrong size, or a failed Vulkan call.
    std::optional<TextureData>
    draw_pass(const VariantPipeline& pipeline, const PassDraw& draw, const PassGrid& grid,
              const std::map<std::string, std::vector<uint8_t>>& uniforms, std::string* error);

    // One dispatch of the job's compute shader; every storage buffer read back. nullopt and
    // `error` naming the binding the job left out, or the Vulkan call that failed.
    std::optional<ComputeOutput> compute(const ComputeJob& job, std::string* error);

  private:
    friend class OffscreenDraw;
    explicit HeadlessDevice(std::unique_ptr<headless_detail::Context> context);
    std::unique_ptr<headless_detail::Context> context_;
};

} // namespace watergen
