// The HeadlessDevice API: creation (device_choice.cpp builds the context), what it reports, and
// its render passes; the draws are in device_draws.cpp and offscreen_draw.cpp, compute in
// compute.cpp.
#include "device_context.h"

#include <fmt/format.h>

namespace watergen {

using namespace headless_detail;

std::unique_ptr<HeadlessDevice> HeadlessDevice::create(const DeviceOptions& options,
                                                       std::string* error) {
    std::unique_ptr<Context> context;
    const Context none;
    if (!guarded(none, error, [&] { context = create_context(options); })) return nullptr;
    return std::unique_ptr<HeadlessDevice>(new HeadlessDevice(std::move(context)));
}

HeadlessDevice::HeadlessDevice(std::unique_ptr<Context> context) : context_(std::move(context)) {}
HeadlessDevice::~HeadlessDevice() = default;

VkPhysicalDevice HeadlessDevice::physical() const {
    return context_->physical;
}

VkDevice HeadlessDevice::device() const {
    return context_->device;
}

const DeviceInfo& HeadlessDevice::info() const {
    return context_->info;
}

std::vector<std::string> HeadlessDevice::validation_messages() const {
    std::lock_guard<std::mutex> lock(context_->messages_mutex);
    return context_->messages;
}

void HeadlessDevice::clear_validation_messages() {
    std::lock_guard<std::mutex> lock(context_->messages_mutex);
    context_->messages.clear();
}

VkRenderPass HeadlessDevice::render_pass() const {
    return context_->render_passes.at(VK_FORMAT_R32G32B32A32_SFLOAT);
}

VkRenderPass HeadlessDevice::render_pass(VkFormat format, std::string* error) {
    VkRenderPass pass = VK_NULL_HANDLE;
    guarded(*context_, error, [&] {
        Context& ctx = *context_;
        VkFormatProperties props{};
        vkGetPhysicalDeviceFormatProperties(ctx.physical, format, &props);
        if (!(props.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT))
            throw DeviceError(fmt::format("device '{}' cannot blend into VkFormat {} (a pass adds "
                                          "its fragments)",
                                          ctx.info.name, static_cast<int>(format)));
        auto it = ctx.render_passes.find(format);
        if (it == ctx.render_passes.end())
            it = ctx.render_passes.emplace(format, create_offscreen_render_pass(ctx, format)).first;
        pass = it->second;
    });
    return pass;
}

namespace headless_detail {

VkRenderPass create_offscreen_render_pass(Context& ctx, VkFormat format) {
    VkAttachmentDescription color{};
    color.format = format;
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    // Every draw clears, so the previous contents never matter.
    color.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    color.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;

    VkSubpassDependency deps[2]{};
    // The same image is drawn into several times and copied out: this draw's clear must
    // wait for the previous draw's writes (WAW) and the previous copy's reads (WAR).
    deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    deps[0].dstSubpass = 0;
    deps[0].srcStageMask =
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    deps[0].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    // The readback copy must see the finished colour writes.
    deps[1].srcSubpass = 0;
    deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;

    VkRenderPassCreateInfo rci{};
    rci.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
    rci.attachmentCount = 1;
    rci.pAttachments = &color;
    rci.subpassCount = 1;
    rci.pSubpasses = &subpass;
    rci.dependencyCount = 2;
    rci.pDependencies = deps;
    VkRenderPass pass = VK_NULL_HANDLE;
    check(vkCreateRenderPass(ctx.device, &rci, nullptr, &pass), "vkCreateRenderPass");
    return pass;
}

} // namespace headless_detail

} // namespace watergen
