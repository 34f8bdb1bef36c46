// Objects and commands of one headless draw (see headless_frame.h).
#include "headless_frame.h"

#include <cstring>
#include <tuple>

#include "pipeline_state.h"

namespace watergen::headless {

void check(VkResult r, const char* call) {
    if (r != VK_SUCCESS)
        throw DrawError(std::string(call) + " failed: VkResult " +
                        std::to_string(static_cast<int>(r)));
}

Frame::~Frame() {
    for (auto it = cleanups_.rbegin(); it != cleanups_.rend(); ++it)
        (*it)();
}

VkDeviceMemory Frame::allocate(const VkMemoryRequirements& req, VkMemoryPropertyFlags want) {
    VkPhysicalDeviceMemoryProperties props{};
    vkGetPhysicalDeviceMemoryProperties(physical_, &props);
    for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
        if ((req.memoryTypeBits & (1u << i)) &&
            (props.memoryTypes[i].propertyFlags & want) == want) {
            VkMemoryAllocateInfo ai{};
            ai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
            ai.allocationSize = req.size;
            ai.memoryTypeIndex = i;
            VkDeviceMemory m = VK_NULL_HANDLE;
            check(vkAllocateMemory(device_, &ai, nullptr, &m), "vkAllocateMemory");
            VkDevice d = device_;
            defer([d, m] { vkFreeMemory(d, m, nullptr); });
            return m;
        }
    throw DrawError("no memory type fits (bits " + std::to_string(req.memoryTypeBits) + ")");
}

VkBuffer Frame::buffer(VkDeviceSize size, VkBufferUsageFlags usage, const void* bytes, void** map) {
    VkBufferCreateInfo ci{};
    ci.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    ci.size = size;
    ci.usage = usage;
    VkBuffer b = VK_NULL_HANDLE;
    check(vkCreateBuffer(device_, &ci, nullptr, &b), "vkCreateBuffer");
    VkDevice d = device_;
    VkMemoryRequirements req{};
    vkGetBufferMemoryRequirements(device_, b, &req);
    VkDeviceMemory m =
        allocate(req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    defer([d, b] { vkDestroyBuffer(d, b, nullptr); });
    check(vkBindBufferMemory(device_, b, m, 0), "vkBindBufferMemory");
    void* p = nullptr;
    check(vkMapMemory(device_, m, 0, VK_WHOLE_SIZE, 0, &p), "vkMapMemory");
    if (bytes)
        std::memcpy(p, bytes, size);
    else
        std::memset(p, 0, size);
    if (map) *map = p;
    return b;
}

std::pair<VkImage, VkImageView> Frame::image(uint32_t w, uint32_t h, uint32_t layers,
                                             VkImageUsageFlags usage, VkFormat format) {
    VkImageCreateInfo ci{};
    ci.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    ci.flags = layers == 6 ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0;
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = format;
    ci.extent = {w, h, 1};
    ci.mipLevels = 1;
    ci.arrayLayers = layers;
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.tiling = VK_IMAGE_TILING_OPTIMAL;
    ci.usage = usage;
    ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage img = VK_NULL_HANDLE;
    check(vkCreateImage(device_, &ci, nullptr, &img), "vkCreateImage");
    VkDevice d = device_;
    VkMemoryRequirements req{};
    vkGetImageMemoryRequirements(device_, img, &req);
    VkDeviceMemory m = allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    defer([d, img] { vkDestroyImage(d, img, nullptr); });
    check(vkBindImageMemory(device_, img, m, 0), "vkBindImageMemory");
    VkImageViewCreateInfo vi{};
    vi.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    vi.image = img;
    vi.viewType = layers == 6 ? VK_IMAGE_VIEW_TYPE_CUBE : VK_IMAGE_VIEW_TYPE_2D;
    vi.format = ci.format;
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers};
    VkImageView view = VK_NULL_HANDLE;
    check(vkCreateImageView(device_, &vi, nullptr, &view), "vkCreateImageView");
    defer([d, view] { vkDestroyImageView(d, view, nullptr); });
    return {img, view};
}

namespace {

void barrier(VkCommandBuffer cmd, VkImage image, uint32_t layers, VkImageLayout from,
             VkImageLayout to, VkAccessFlags src_access, VkAccessFlags dst_access,
             VkPipelineStageFlags src, VkPipelineStageFlags dst) {
    VkImageMemoryBarrier b{};
    b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers};
    vkCmdPipelineBarrier(cmd, src, dst, 0, 0, nullptr, 0, nullptr, 1, &b);
}

// Uploads a texture (recorded into `cmd`), ready for sampling once `cmd` has run.
VkImageView upload(Frame& f, VkCommandBuffer cmd, const std::string& name, const HeadlessTexture& t,
                   const DescriptorBinding& b) {
    const bool cube = b.image_dim == "Cube";
    if (t.layers != (cube ? 6u : 1u) ||
        t.rgba.size() != size_t(t.width) * t.height * t.layers * 4 || t.width == 0 || t.height == 0)
        throw DrawError("texture '" + name + "': expected " + (cube ? "6 layers" : "1 layer") +
                        " of width*height RGBA floats");
    const auto [img, view] = f.image(t.width, t.height, t.layers,
                                     VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    VkBuffer staging = f.buffer(t.rgba.size() * sizeof(float), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                t.rgba.data(), nullptr);
    barrier(cmd, img, t.layers, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
            VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
            VK_PIPELINE_STAGE_TRANSFER_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, t.layers};
    region.imageExtent = {t.width, t.height, 1};
    vkCmdCopyBufferToImage(cmd, staging, img, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    barrier(cmd, img, t.layers, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
            VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
    return view;
}

VkSampler linear_clamp(Frame& f) {
    const VkSamplerCreateInfo ci = vk_state::clamp_sampler_info(VK_FILTER_LINEAR);
    VkSampler s = VK_NULL_HANDLE;
    check(vkCreateSampler(f.device(), &ci, nullptr, &s), "vkCreateSampler");
    VkDevice d = f.device();
    f.defer([d, s] { vkDestroySampler(d, s, nullptr); });
    return s;
}

} // namespace

// Descriptor sets of the pipeline with every binding written from `in` (uploads into `cmd`).
std::vector<VkDescriptorSet> descriptor_sets(Frame& f, VkCommandBuffer cmd,
                                             const VariantPipeline& p, const HeadlessDraw& in) {
    const auto& layouts = p.set_layouts();
    if (layouts.empty()) return {};
    const std::vector<VkDescriptorPoolSize> sizes = p.pool_sizes();
    VkDescriptorPoolCreateInfo pci{};
    pci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pci.maxSets = static_cast<uint32_t>(layouts.size());
    pci.poolSizeCount = static_cast<uint32_t>(sizes.size());
    pci.pPoolSizes = sizes.data();
    VkDescriptorPool pool = VK_NULL_HANDLE;
    check(vkCreateDescriptorPool(f.device(), &pci, nullptr, &pool), "vkCreateDescriptorPool");
    VkDevice d = f.device();
    f.defer([d, pool] { vkDestroyDescriptorPool(d, pool, nullptr); });
    std::vector<VkDescriptorSet> sets(layouts.size());
    VkDescriptorSetAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    ai.descriptorPool = pool;
    ai.descriptorSetCount = static_cast<uint32_t>(layouts.size());
    ai.pSetLayouts = layouts.data();
    check(vkAllocateDescriptorSets(f.device(), &ai, sets.data()), "vkAllocateDescriptorSets");
    VkSampler sampler = VK_NULL_HANDLE;
    for (uint32_t s = 0; s < sets.size(); ++s)
        for (const DescriptorBinding& b : p.bindings(s)) {
            VkDescriptorBufferInfo buffer{};
            VkDescriptorImageInfo image{};
            VkWriteDescriptorSet w{};
            w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
            w.dstSet = sets[s];
            w.dstBinding = b.binding;
            w.descriptorCount = 1;
            w.descriptorType = descriptor_type(b.kind);
            if (b.kind == DescriptorKind::UniformBuffer) {
                const auto it = in.uniforms.find(b.name);
                if (it == in.uniforms.end())
                    throw DrawError("uniform block '" + b.name + "' (" +
                                    std::to_string(b.block_size) + " bytes) is not supplied");
                if (it->second.size() < b.block_size)
                    throw DrawError("uniform block '" + b.name + "' needs " +
                                    std::to_string(b.block_size) + " bytes; " +
                                    std::to_string(it->second.size()) + " supplied");
                buffer.buffer = f.buffer(it->second.size(), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                         it->second.data(), nullptr);
                buffer.range = VK_WHOLE_SIZE;
                w.pBufferInfo = &buffer;
            } else if (b.kind == DescriptorKind::Sampler) {
                if (!sampler) sampler = linear_clamp(f);
                image.sampler = sampler;
                w.pImageInfo = &image;
            } else if (b.kind == DescriptorKind::SampledImage) {
                const auto it = in.textures.find(b.name);
                if (it == in.textures.end())
                    throw DrawError("texture '" + b.name + "' (binding " +
                                    std::to_string(b.binding) + ") is not supplied");
                image.imageView = upload(f, cmd, b.name, it->second, b);
                image.imageLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
                w.pImageInfo = &image;
            } else {
                throw DrawError("binding '" + b.name + "' is " + to_string(b.kind) +
                                "; the headless draw feeds uniform buffers, samplers and "
                                "sampled images");
            }
            vkUpdateDescriptorSets(f.device(), 1, &w, 0, nullptr);
        }
    return sets;
}

VkCommandBuffer begin_commands(Frame& f, VkCommandPool pool) {
    VkCommandBufferAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    ai.commandPool = pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    check(vkAllocateCommandBuffers(f.device(), &ai, &cmd), "vkAllocateCommandBuffers");
    VkDevice d = f.device();
    f.defer([d, pool, cmd] { vkFreeCommandBuffers(d, pool, 1, &cmd); });
    VkCommandBufferBeginInfo bi{};
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
    return cmd;
}

Target make_target(Frame& f, VkRenderPass render_pass, uint32_t width, uint32_t height,
                   VkFormat format) {
    Target t{VK_NULL_HANDLE, VK_NULL_HANDLE, width, height, format};
    VkImageView view = VK_NULL_HANDLE;
    std::tie(t.image, view) =
        f.image(width, height, 1,
                VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, format);
    VkFramebufferCreateInfo fci{};
    fci.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    fci.renderPass = render_pass;
    fci.attachmentCount = 1;
    fci.pAttachments = &view;
    fci.width = width;
    fci.height = height;
    fci.layers = 1;
    check(vkCreateFramebuffer(f.device(), &fci, nullptr, &t.framebuffer), "vkCreateFramebuffer");
    VkDevice d = f.device();
    VkFramebuffer fb = t.framebuffer;
    f.defer([d, fb] { vkDestroyFramebuffer(d, fb, nullptr); });
    return t;
}

void begin_draw(VkCommandBuffer cmd, VkRenderPass render_pass, const Target& t, float clear,
                const VariantPipeline& pipeline, const std::vector<VkDescriptorSet>& sets) {
    VkClearValue value{};
    value.color = {{clear, clear, clear, clear}};
    VkRenderPassBeginInfo rbi{};
    rbi.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    rbi.renderPass = render_pass;
    rbi.framebuffer = t.framebuffer;
    rbi.renderArea = {{0, 0}, {t.width, t.height}};
    rbi.clearValueCount = 1;
    rbi.pClearValues = &value;
    vkCmdBeginRenderPass(cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.pipeline());
    const VkViewport viewport{0, 0, float(t.width), float(t.height), 0, 1};
    const VkRect2D scissor{{0, 0}, {t.width, t.height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    if (!sets.empty())
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.layout(), 0,
                                static_cast<uint32_t>(sets.size()), sets.data(), 0, nullptr);
}

std::vector<float> read_target(Frame& f, VkQueue queue, VkCommandBuffer cmd, const Target& t,
                               uint32_t channels) {
    const VkDeviceSize bytes = VkDeviceSize{t.width} * t.height * channels * sizeof(float);
    void* mapped = nullptr;
    VkBuffer readback = f.buffer(bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, nullptr, &mapped);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {t.width, t.height, 1};
    vkCmdCopyImageToBuffer(cmd, t.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback, 1,
                           &region);
    VkMemoryBarrier to_host{};
    to_host.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                         &to_host, 0, nullptr, 0, nullptr);
    check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    VkSubmitInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    check(vkQueueSubmit(queue, 1, &si, VK_NULL_HANDLE), "vkQueueSubmit");
    check(vkQueueWaitIdle(queue), "vkQueueWaitIdle");
    std::vector<float> texels(size_t{t.width} * t.height * channels);
    std::memcpy(texels.data(), mapped, bytes);
    return texels;
}

} // namespace watergen::headless
