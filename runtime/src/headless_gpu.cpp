// Headless device (validation when installed), offscreen RGBA32F target, one draw, readback
// (the draw's objects and commands: headless_frame.h; a companion pass's draw:
// headless_pass.cpp).
#include "watergen/runtime/headless_gpu.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <stdexcept>

#include "headless_frame.h"
#include "pipeline_state.h"

namespace watergen {

using namespace headless;

namespace {

constexpr const char* kValidation = "VK_LAYER_KHRONOS_validation";

bool has_layer(const char* name) {
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
        return std::strcmp(l.layerName, name) == 0;
    });
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

} // namespace

VKAPI_ATTR VkBool32 VKAPI_CALL
HeadlessGpu::on_message(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                        const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* gpu = static_cast<HeadlessGpu*>(user);
    const char* id = data->pMessageIdName ? data->pMessageIdName : "";
    if (std::strcmp(id, "Loader Message") != 0)
        gpu->messages_.push_back(std::string(id) + ": " + (data->pMessage ? data->pMessage : ""));
    return VK_FALSE;
}

std::unique_ptr<HeadlessGpu> HeadlessGpu::create(std::string* error) {
    std::unique_ptr<HeadlessGpu> g(new HeadlessGpu());
    try {
        const bool validation = has_layer(kValidation);
        VkApplicationInfo app{};
        app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
        app.pApplicationName = "watergen-headless";
        app.apiVersion = VK_API_VERSION_1_1;
        VkDebugUtilsMessengerCreateInfoEXT mi{};
        mi.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
        mi.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                             VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
        mi.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                         VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
        mi.pfnUserCallback = on_message;
        mi.pUserData = g.get();
        const char* layer = kValidation;
        const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
        VkInstanceCreateInfo ici{};
        ici.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
        ici.pApplicationInfo = &app;
        if (validation) {
            ici.pNext = &mi;
            ici.enabledLayerCount = 1;
            ici.ppEnabledLayerNames = &layer;
            ici.enabledExtensionCount = 1;
            ici.ppEnabledExtensionNames = &extension;
        }
        check(vkCreateInstance(&ici, nullptr, &g->instance_), "vkCreateInstance");
        if (validation) {
            auto make = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(g->instance_, "vkCreateDebugUtilsMessengerEXT"));
            if (make) check(make(g->instance_, &mi, nullptr, &g->messenger_), "messenger");
        }
        uint32_t n = 0;
        check(vkEnumeratePhysicalDevices(g->instance_, &n, nullptr), "vkEnumeratePhysicalDevices");
        std::vector<VkPhysicalDevice> devices(n);
        check(vkEnumeratePhysicalDevices(g->instance_, &n, devices.data()),
              "vkEnumeratePhysicalDevices");
        const char* wanted = std::getenv("WATERGEN_VK_DEVICE");
        std::string names;
        for (VkPhysicalDevice pd : devices) {
            VkPhysicalDeviceProperties props{};
            vkGetPhysicalDeviceProperties(pd, &props);
            names += (names.empty() ? "'" : ", '") + std::string(props.deviceName) + "'";
            const bool fits = wanted && *wanted
                                  ? lower(props.deviceName).find(lower(wanted)) != std::string::npos
                                  : props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
            if (fits && !g->physical_) {
                g->physical_ = pd;
                g->device_name_ = props.deviceName;
            }
        }
        if (!g->physical_)
            throw DrawError(std::string("no Vulkan device matches ") +
                            (wanted && *wanted ? "WATERGEN_VK_DEVICE='" + std::string(wanted) + "'"
                                               : std::string("a CPU device (lavapipe)")) +
                            " (devices: " + (names.empty() ? "none" : names) + ")");
        uint32_t families = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(g->physical_, &families, nullptr);
        std::vector<VkQueueFamilyProperties> props(families);
        vkGetPhysicalDeviceQueueFamilyProperties(g->physical_, &families, props.data());
        g->family_ = UINT32_MAX;
        for (uint32_t i = 0; i < families && g->family_ == UINT32_MAX; ++i)
            if (props[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) g->family_ = i;
        if (g->family_ == UINT32_MAX) throw DrawError("the device has no graphics queue");
        check(vk_state::create_device(g->physical_, g->family_, nullptr, {}, {}, &g->device_),
              "vkCreateDevice");
        vkGetDeviceQueue(g->device_, g->family_, 0, &g->queue_);
        VkCommandPoolCreateInfo pci{};
        pci.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
        pci.queueFamilyIndex = g->family_;
        check(vkCreateCommandPool(g->device_, &pci, nullptr, &g->pool_), "vkCreateCommandPool");

        check(vk_state::create_offscreen_render_pass(g->device_, &g->render_pass_),
              "vkCreateRenderPass");
    } catch (const DrawError& e) {
        *error = e.what();
        return nullptr;
    }
    return g;
}

HeadlessGpu::~HeadlessGpu() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        if (render_pass_) vkDestroyRenderPass(device_, render_pass_, nullptr);
        for (const auto& [format, pass] : target_passes_)
            vkDestroyRenderPass(device_, pass, nullptr);
        if (pool_) vkDestroyCommandPool(device_, pool_, nullptr);
        vkDestroyDevice(device_, nullptr);
    }
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
}

std::vector<float> HeadlessGpu::draw(const VariantPipeline& pipeline, const HeadlessDraw& in,
                                     std::string* error) {
    try {
        Frame f(physical_, device_);
        VkCommandBuffer cmd = begin_commands(f, pool_);
        const std::vector<VkDescriptorSet> sets = descriptor_sets(f, cmd, pipeline, in);
        const Target target =
            make_target(f, render_pass_, in.width, in.height, VK_FORMAT_R32G32B32A32_SFLOAT);
        begin_draw(cmd, render_pass_, target, 0.0f, pipeline, sets);
        vkCmdDraw(cmd, 3, 1, 0, 0);
        vkCmdEndRenderPass(cmd);
        return read_target(f, queue_, cmd, target, 4);
    } catch (const DrawError& e) {
        *error = e.what();
        return {};
    }
}

} // namespace watergen
