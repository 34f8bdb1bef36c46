// The objects and commands of one HeadlessGpu draw, shared by the water draw (headless_gpu.cpp)
// and a companion pass's draw (headless_pass.cpp): every object a draw makes is released by its
// Frame in reverse order; failures throw a DrawError that the draw turns into an error string.
// Private to watergen_engine; not installed.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include "watergen/runtime/headless_gpu.h"

namespace watergen::headless {

struct DrawError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Throws a DrawError naming the call and its VkResult unless `r` is VK_SUCCESS.
void check(VkResult r, const char* call);

// Objects of one draw, destroyed in reverse order of creation.
class Frame {
  public:
    Frame(VkPhysicalDevice physical, VkDevice device) : physical_(physical), device_(device) {}
    ~Frame();
    Frame(const Frame&) = delete;
    Frame& operator=(const Frame&) = delete;
    void defer(std::function<void()> f) { cleanups_.push_back(std::move(f)); }
    VkDevice device() const { return device_; }

    // Memory of a type with `want` for a buffer or image.
    VkDeviceMemory allocate(const VkMemoryRequirements& req, VkMemoryPropertyFlags want);
    // A host-visible coherent buffer holding `bytes` (or `size` zero bytes); returns its mapping.
    VkBuffer buffer(VkDeviceSize size, VkBufferUsageFlags usage, const void* bytes, void** map);
    // A 2D image of `format` (a cube with 6 layers) and its view.
    std::pair<VkImage, VkImageView> image(uint32_t w, uint32_t h, uint32_t layers,
                                          VkImageUsageFlags usage,
                                          VkFormat format = VK_FORMAT_R32G32B32A32_SFLOAT);

  private:
    VkPhysicalDevice physical_;
    VkDevice device_;
    std::vector<std::function<void()>> cleanups_;
};

// Descriptor sets of the pipeline with every binding written from `in` (uploads into `cmd`).
std::vector<VkDescriptorSet> descriptor_sets(Frame& f, VkCommandBuffer cmd,
                                             const VariantPipeline& p, const HeadlessDraw& in);

// A one-time command buffer from `pool`, begun; freed with the frame.
VkCommandBuffer begin_commands(Frame& f, VkCommandPool pool);

// A width x height colour target of `format` and its framebuffer for `render_pass`.
struct Target {
    VkImage image = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    uint32_t width = 0, height = 0;
    VkFormat format = VK_FORMAT_UNDEFINED;
};
Target make_target(Frame& f, VkRenderPass render_pass, uint32_t width, uint32_t height,
                   VkFormat format);

// Begins the render pass over the whole target (cleared to `clear` in every channel), binds the
// pipeline and its descriptor sets, sets viewport and scissor to the target.
void begin_draw(VkCommandBuffer cmd, VkRenderPass render_pass, const Target& t, float clear,
                const VariantPipeline& pipeline, const std::vector<VkDescriptorSet>& sets);

// After vkCmdEndRenderPass: copies the target out, submits `cmd`, waits, and returns its texels
// (`channels` floats each, row 0 at the top).
std::vector<float> read_target(Frame& f, VkQueue queue, VkCommandBuffer cmd, const Target& t,
                               uint32_t channels);

} // namespace watergen::headless
