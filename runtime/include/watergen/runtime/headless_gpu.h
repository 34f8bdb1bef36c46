// A minimal headless Vulkan device and offscreen draw, for tools, tests and the example
// consumer: it draws a VariantPipeline into an RGBA32F image and reads it back, and a build's
// companion pass (pass_pipeline.h) into its float target, read back as the texture the water
// variant samples. Part of watergen::runtime; an engine brings its own device and frame and uses
// only VariantPipeline and create_pass_pipeline().
//
// Device: the one whose name contains WATERGEN_VK_DEVICE when that is set, else the first CPU
// device (lavapipe): results are reproducible. The validation layer is enabled when installed,
// and its warnings and errors are collected (messages()).
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "watergen/runtime/build_pass.h"
#include "watergen/runtime/variant_pipeline.h"

namespace watergen {

// RGBA32F texels, layer-major then rows then columns; 6 layers make a cube (+X -X +Y -Y +Z -Z).
struct HeadlessTexture {
    uint32_t width = 1, height = 1, layers = 1;
    std::vector<float> rgba;
};

struct HeadlessDraw {
    uint32_t width = 256, height = 256;
    // Bytes of each uniform buffer binding, by binding name (UniformWriter::pack()).
    std::map<std::string, std::vector<uint8_t>> uniforms;
    // Images of the sampled-image bindings, by binding name; every Sampler binding gets a
    // linear, clamp-to-edge sampler.
    std::map<std::string, HeadlessTexture> textures;
};

class HeadlessGpu {
  public:
    // nullptr and `error` when no device fits or Vulkan fails to start.
    static std::unique_ptr<HeadlessGpu> create(std::string* error);
    ~HeadlessGpu();
    HeadlessGpu(const HeadlessGpu&) = delete;
    HeadlessGpu& operator=(const HeadlessGpu&) = delete;

    VkPhysicalDevice physical() const { return physical_; }
    VkDevice device() const { return device_; }
    const std::string& device_name() const { return device_name_; }
    // One RGBA32F colour attachment, cleared to zero, left ready to be copied out.
    VkRenderPass render_pass() const { return render_pass_; }

    // Draws the pipeline's fullscreen triangle once; RGBA32F pixels, row 0 at the top. Empty and
    // `error` when a binding has no input or a Vulkan call fails.
    std::vector<float> draw(const VariantPipeline& pipeline, const HeadlessDraw& inputs,
                            std::string* error);

    // One colour attachment of `format` (a companion pass's target, pass_format()), cleared,
    // left ready to be copied out; made on first use and kept. Null and `error` when the device
    // cannot blend into the format (a pass adds its fragments) or Vulkan fails.
    VkRenderPass render_pass(VkFormat format, std::string* error);

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
    std::optional<HeadlessTexture>
    draw_pass(const VariantPipeline& pipeline, const PassDraw& draw, const PassGrid& grid,
              const std::map<std::string, std::vector<uint8_t>>& uniforms, std::string* error);

    std::vector<std::string> messages() const { return messages_; }

  private:
    HeadlessGpu() = default;
    static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                     VkDebugUtilsMessageTypeFlagsEXT,
                                                     const VkDebugUtilsMessengerCallbackDataEXT*,
                                                     void*);
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t family_ = 0;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkRenderPass render_pass_ = VK_NULL_HANDLE;
    std::map<VkFormat, VkRenderPass> target_passes_; // render_pass(format)
    std::string device_name_;
    std::vector<std::string> messages_;
};

} // namespace watergen
