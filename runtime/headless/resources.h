// Buffers, images, textures, command buffers, fences and shader modules of the headless device,
// each registered with the Scope that destroys it (resources.cpp). Not installed.
#pragma once

#include "device_context.h"

#include <map>
#include <string>
#include <vector>

namespace watergen::headless_detail {

// Host-visible, persistently mapped buffer.
struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    void* mapped = nullptr;
    bool coherent = true;
};

// Zero-filled; throws for size 0.
Buffer create_buffer(Scope& scope, VkDeviceSize size, VkBufferUsageFlags usage);
// A buffer holding `size` bytes of `data`.
Buffer upload_buffer(Scope& scope, const void* data, size_t size, VkBufferUsageFlags usage);
// memcpy into the mapping (and flush when the memory is not coherent).
void write_buffer(Context& ctx, const Buffer& b, const void* data, size_t size);
// invalidate (when not coherent) and memcpy out of the mapping.
void read_buffer(Context& ctx, const Buffer& b, void* out, size_t size);

struct Image {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t layers = 1;
};

// A colour attachment of `format` that can be copied out.
Image create_color_target(Scope& scope, uint32_t width, uint32_t height, VkFormat format);
// RGBA32F sampled texture (2D or cube), uploaded and left in SHADER_READ_ONLY_OPTIMAL.
Image create_texture(Scope& scope, const std::string& name, const TextureData& data, bool cube);

VkCommandBuffer allocate_command_buffer(Scope& scope);
// Begins `cmd`; one_time: VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT (else it may be
// resubmitted, as a timed draw is).
void begin_commands(VkCommandBuffer cmd, bool one_time);
VkFence create_fence(Scope& scope);
// Submits one command buffer and blocks until the fence signals (with a generous timeout).
void submit_and_wait(Context& ctx, VkCommandBuffer cmd, VkFence fence);
// Checks the SPIR-V magic number first: a clearer message than the driver's.
VkShaderModule create_shader_module(Scope& scope, const std::vector<uint32_t>& spirv,
                                    const char* what);

// VkSpecializationInfo over float values by constant_id; `info()` is null when there are none.
// Points into itself, so it stays where it was made while the pipeline is created.
class Specialization {
  public:
    explicit Specialization(const std::map<uint32_t, float>& values);
    Specialization(const Specialization&) = delete;
    Specialization& operator=(const Specialization&) = delete;
    const VkSpecializationInfo* info() const { return entries_.empty() ? nullptr : &info_; }

  private:
    std::vector<VkSpecializationMapEntry> entries_;
    std::vector<float> data_;
    VkSpecializationInfo info_{};
};

} // namespace watergen::headless_detail
