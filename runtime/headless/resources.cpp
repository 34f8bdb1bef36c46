// Buffers, images, texture upload, command buffers, fences, shader modules and the Scope that
// destroys them (see resources.h).
#include "resources.h"

#include <fmt/format.h>

#include <cstring>

namespace watergen::headless_detail {
namespace {

constexpr VkFormat kRgba32f = VK_FORMAT_R32G32B32A32_SFLOAT;
// Long enough for lavapipe to JIT and run a very large shader at a large size; short
// enough that an infinite loop in a generated shader fails the draw instead of hanging CI.
constexpr uint64_t kWaitTimeoutNs = 120ull * 1000 * 1000 * 1000;

uint32_t find_memory_type(const Context& ctx, uint32_t type_bits, VkMemoryPropertyFlags required,
                          VkMemoryPropertyFlags preferred) {
    int fallback = -1;
    for (uint32_t i = 0; i < ctx.memory.memoryTypeCount; ++i) {
        if (!(type_bits & (1u << i))) continue;
        VkMemoryPropertyFlags flags = ctx.memory.memoryTypes[i].propertyFlags;
        if ((flags & required) != required) continue;
        if ((flags & preferred) == preferred) return i;
        if (fallback < 0) fallback = static_cast<int>(i);
    }
    if (fallback < 0)
        throw DeviceError(fmt::format("no Vulkan memory type with property flags {:#x}", required));
    return static_cast<uint32_t>(fallback);
}

VkDeviceMemory allocate(Scope& scope, const VkMemoryRequirements& req,
                        VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred,
                        bool* coherent) {
    Context& ctx = scope.ctx();
    VkMemoryAllocateInfo mai{};
    mai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = find_memory_type(ctx, req.memoryTypeBits, required, preferred);
    if (coherent)
        *coherent = ctx.memory.memoryTypes[mai.memoryTypeIndex].propertyFlags &
                    VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    check(vkAllocateMemory(ctx.device, &mai, nullptr, &memory), "vkAllocateMemory");
    VkDevice device = ctx.device;
    scope.defer([device, memory] { vkFreeMemory(device, memory, nullptr); });
    return memory;
}

std::string format_name(VkFormat format) {
    if (format == kRgba32f) return "VK_FORMAT_R32G32B32A32_SFLOAT";
    return fmt::format("VkFormat {}", static_cast<int>(format));
}

void require_format(const Context& ctx, VkFormat format, VkFormatFeatureFlags features,
                    const char* purpose) {
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(ctx.physical, format, &props);
    if ((props.optimalTilingFeatures & features) != features)
        throw DeviceError(fmt::format("device '{}' cannot use {} as {}", ctx.info.name,
                                      format_name(format), purpose));
}

VkImageView create_view(Scope& scope, VkImage image, VkFormat format, VkImageViewType type,
                        uint32_t layers) {
    VkImageViewCreateInfo vci{};
    vci.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    vci.image = image;
    vci.viewType = type;
    vci.format = format;
    vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers};
    VkImageView view = VK_NULL_HANDLE;
    check(vkCreateImageView(scope.ctx().device, &vci, nullptr, &view), "vkCreateImageView");
    VkDevice device = scope.ctx().device;
    scope.defer([device, view] { vkDestroyImageView(device, view, nullptr); });
    return view;
}

Image create_image(Scope& scope, VkFormat format, uint32_t width, uint32_t height, uint32_t layers,
                   bool cube, VkImageUsageFlags usage) {
    Context& ctx = scope.ctx();
    VkImageCreateInfo ici{};
    ici.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    ici.flags = cube ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0;
    ici.imageType = VK_IMAGE_TYPE_2D;
    ici.format = format;
    ici.extent = {width, height, 1};
    ici.mipLevels = 1;
    ici.arrayLayers = layers;
    ici.samples = VK_SAMPLE_COUNT_1_BIT;
    ici.tiling = VK_IMAGE_TILING_OPTIMAL;
    ici.usage = usage;
    ici.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ici.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    Image img;
    img.width = width;
    img.height = height;
    img.layers = layers;
    check(vkCreateImage(ctx.device, &ici, nullptr, &img.image), "vkCreateImage");
    VkDevice device = ctx.device;
    VkImage image = img.image;
    scope.defer([device, image] { vkDestroyImage(device, image, nullptr); });

    VkMemoryRequirements req{};
    vkGetImageMemoryRequirements(ctx.device, img.image, &req);
    VkDeviceMemory memory = allocate(scope, req, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, nullptr);
    check(vkBindImageMemory(ctx.device, img.image, memory, 0), "vkBindImageMemory");
    img.view = create_view(scope, img.image, format,
                           cube ? VK_IMAGE_VIEW_TYPE_CUBE : VK_IMAGE_VIEW_TYPE_2D, layers);
    return img;
}

} // namespace

Scope::~Scope() {
    // See Context::unusable: objects the device may still be using are leaked.
    if (ctx_.unusable) return;
    for (auto it = cleanups_.rbegin(); it != cleanups_.rend(); ++it)
        (*it)();
}

Buffer create_buffer(Scope& scope, VkDeviceSize size, VkBufferUsageFlags usage) {
    Context& ctx = scope.ctx();
    if (size == 0) throw DeviceError("cannot create an empty Vulkan buffer");
    VkBufferCreateInfo bci{};
    bci.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    bci.size = size;
    bci.usage = usage;
    bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    Buffer b;
    b.size = size;
    check(vkCreateBuffer(ctx.device, &bci, nullptr, &b.buffer), "vkCreateBuffer");
    VkDevice device = ctx.device;
    VkBuffer buffer = b.buffer;
    scope.defer([device, buffer] { vkDestroyBuffer(device, buffer, nullptr); });

    VkMemoryRequirements req{};
    vkGetBufferMemoryRequirements(ctx.device, b.buffer, &req);
    // Everything small enough to live in a test goes through host-visible memory; on
    // lavapipe all memory is host-visible and coherent anyway.
    b.memory = allocate(scope, req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT,
                        VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, &b.coherent);
    check(vkBindBufferMemory(ctx.device, b.buffer, b.memory, 0), "vkBindBufferMemory");
    check(vkMapMemory(ctx.device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
    VkDeviceMemory memory = b.memory;
    // Registered after vkFreeMemory, so it runs before it.
    scope.defer([device, memory] { vkUnmapMemory(device, memory); });
    std::memset(b.mapped, 0, size);
    return b;
}

Buffer upload_buffer(Scope& scope, const void* data, size_t size, VkBufferUsageFlags usage) {
    Buffer b = create_buffer(scope, size, usage);
    write_buffer(scope.ctx(), b, data, size);
    return b;
}

void write_buffer(Context& ctx, const Buffer& b, const void* data, size_t size) {
    if (size > b.size) throw DeviceError("write past the end of a Vulkan buffer");
    if (size) std::memcpy(b.mapped, data, size);
    if (!b.coherent) {
        // Whole-range flush keeps us clear of nonCoherentAtomSize alignment rules.
        VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, nullptr, b.memory, 0,
                                  VK_WHOLE_SIZE};
        check(vkFlushMappedMemoryRanges(ctx.device, 1, &range), "vkFlushMappedMemoryRanges");
    }
}

void read_buffer(Context& ctx, const Buffer& b, void* out, size_t size) {
    if (size > b.size) throw DeviceError("read past the end of a Vulkan buffer");
    if (!b.coherent) {
        VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, nullptr, b.memory, 0,
                                  VK_WHOLE_SIZE};
        check(vkInvalidateMappedMemoryRanges(ctx.device, 1, &range),
              "vkInvalidateMappedMemoryRanges");
    }
    if (size) std::memcpy(out, b.mapped, size);
}

Image create_color_target(Scope& scope, uint32_t width, uint32_t height, VkFormat format) {
    const Context& ctx = scope.ctx();
    if (width == 0 || height == 0 || width > ctx.limits.maxFramebufferWidth ||
        height > ctx.limits.maxFramebufferHeight)
        throw DeviceError(fmt::format("render size {}x{} is outside 1x1..{}x{}", width, height,
                                      ctx.limits.maxFramebufferWidth,
                                      ctx.limits.maxFramebufferHeight));
    require_format(ctx, format,
                   VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT,
                   "a colour attachment");
    return create_image(scope, format, width, height, 1, false,
                        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
}

Image create_texture(Scope& scope, const std::string& name, const TextureData& data, bool cube) {
    Context& ctx = scope.ctx();
    const uint32_t want_layers = cube ? 6 : 1;
    if (data.layers != want_layers)
        throw DeviceError(
            fmt::format("texture '{}' has {} layers; the shader's {} binding needs {}", name,
                        data.layers, cube ? "cube" : "2D", want_layers));
    const uint32_t max_dim =
        cube ? ctx.limits.maxImageDimensionCube : ctx.limits.maxImageDimension2D;
    if (data.width == 0 || data.height == 0 || data.width > max_dim || data.height > max_dim ||
        (cube && data.width != data.height))
        throw DeviceError(fmt::format("texture '{}' has invalid size {}x{}{}", name, data.width,
                                      data.height, cube ? " (cube faces must be square)" : ""));
    const size_t floats = size_t{data.width} * data.height * data.layers * 4;
    if (data.rgba.size() != floats)
        throw DeviceError(fmt::format("texture '{}' has {} floats; {}x{}x{} RGBA needs {}", name,
                                      data.rgba.size(), data.width, data.height, data.layers,
                                      floats));
    require_format(ctx, kRgba32f,
                   VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_TRANSFER_DST_BIT,
                   "a sampled texture");

    Image img = create_image(scope, kRgba32f, data.width, data.height, data.layers, cube,
                             VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    // Host writes made before vkQueueSubmit are visible to the device without a barrier.
    Buffer staging = upload_buffer(scope, data.rgba.data(), floats * sizeof(float),
                                   VK_BUFFER_USAGE_TRANSFER_SRC_BIT);

    VkCommandBuffer cmd = allocate_command_buffer(scope);
    begin_commands(cmd, true);
    VkImageMemoryBarrier to_dst{};
    to_dst.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    to_dst.srcAccessMask = 0; // fresh image: nothing to wait for, contents discarded
    to_dst.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_dst.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    to_dst.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    to_dst.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_dst.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_dst.image = img.image;
    to_dst.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, data.layers};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                         0, nullptr, 0, nullptr, 1, &to_dst);

    // Tightly packed, layers one after another: exactly TextureData's layout.
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, data.layers};
    region.imageExtent = {data.width, data.height, 1};
    vkCmdCopyBufferToImage(cmd, staging.buffer, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &region);

    // The copy must land before any shader stage samples the texture.
    VkImageMemoryBarrier to_read = to_dst;
    to_read.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_read.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
    to_read.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    to_read.newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
                             VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT |
                             VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         0, 0, nullptr, 0, nullptr, 1, &to_read);
    check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    submit_and_wait(ctx, cmd, create_fence(scope));
    return img;
}

VkCommandBuffer allocate_command_buffer(Scope& scope) {
    Context& ctx = scope.ctx();
    VkCommandBufferAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    ai.commandPool = ctx.command_pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    check(vkAllocateCommandBuffers(ctx.device, &ai, &cmd), "vkAllocateCommandBuffers");
    VkDevice device = ctx.device;
    VkCommandPool pool = ctx.command_pool;
    scope.defer([device, pool, cmd] { vkFreeCommandBuffers(device, pool, 1, &cmd); });
    return cmd;
}

void begin_commands(VkCommandBuffer cmd, bool one_time) {
    VkCommandBufferBeginInfo bi{};
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    bi.flags = one_time ? VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT : 0;
    check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
}

VkFence create_fence(Scope& scope) {
    VkFenceCreateInfo fci{};
    fci.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    VkFence fence = VK_NULL_HANDLE;
    check(vkCreateFence(scope.ctx().device, &fci, nullptr, &fence), "vkCreateFence");
    VkDevice device = scope.ctx().device;
    scope.defer([device, fence] { vkDestroyFence(device, fence, nullptr); });
    return fence;
}

void submit_and_wait(Context& ctx, VkCommandBuffer cmd, VkFence fence) {
    // Fences are reused across the timed draws of one draw.
    check(vkResetFences(ctx.device, 1, &fence), "vkResetFences");
    VkSubmitInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    VkResult r = vkQueueSubmit(ctx.queue, 1, &si, fence);
    if (r == VK_ERROR_DEVICE_LOST) ctx.unusable = true;
    check(r, "vkQueueSubmit");
    r = vkWaitForFences(ctx.device, 1, &fence, VK_TRUE, kWaitTimeoutNs);
    if (r == VK_TIMEOUT || r == VK_ERROR_DEVICE_LOST) ctx.unusable = true;
    check(r, "vkWaitForFences");
}

VkShaderModule create_shader_module(Scope& scope, const std::vector<uint32_t>& spirv,
                                    const char* what) {
    // 0x07230203 is the SPIR-V magic number; catching a wrong blob here gives a clearer
    // message than the driver would.
    if (spirv.size() < 5 || spirv[0] != 0x07230203u)
        throw DeviceError(fmt::format("{} SPIR-V is empty or not SPIR-V", what));
    VkShaderModuleCreateInfo ci{};
    ci.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    ci.codeSize = spirv.size() * sizeof(uint32_t);
    ci.pCode = spirv.data();
    VkShaderModule module = VK_NULL_HANDLE;
    check(vkCreateShaderModule(scope.ctx().device, &ci, nullptr, &module),
          fmt::format("vkCreateShaderModule ({})", what).c_str());
    VkDevice device = scope.ctx().device;
    scope.defer([device, module] { vkDestroyShaderModule(device, module, nullptr); });
    return module;
}

Specialization::Specialization(const std::map<uint32_t, float>& values) {
    for (const auto& [id, value] : values) {
        entries_.push_back(
            {id, static_cast<uint32_t>(data_.size() * sizeof(float)), sizeof(float)});
        data_.push_back(value);
    }
    info_.mapEntryCount = static_cast<uint32_t>(entries_.size());
    info_.pMapEntries = entries_.data();
    info_.dataSize = data_.size() * sizeof(float);
    info_.pData = data_.data();
}

} // namespace watergen::headless_detail
