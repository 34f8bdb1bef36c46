// A minimal headless Vulkan device and offscreen draw, for tools, tests and the example
// consumer: it draws a VariantPipeline into an RGBA32F image and reads it back. Part of
// watergen::runtime; an engine brings its own device and frame and uses only VariantPipeline.
//
// Device: the one whose name contains WATERGEN_VK_DEVICE when that is set, else the first CPU
// device (lavapipe): results are reproducible. The validation layer is enabled when installed,
// and its warnings and errors are collected (messages()).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

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
    std::string device_name_;
    std::vector<std::string> messages_;
};

} // namespace watergen
