// The Vulkan instance of the headless device: its API version, the validation layer when
// installed, and the debug messenger that collects the layer's (and the loader's) messages.
#include "device_context.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

namespace watergen::headless_detail {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool has_layer(const char* name) {
    uint32_t count = 0;
    if (vkEnumerateInstanceLayerProperties(&count, nullptr) != VK_SUCCESS) return false;
    std::vector<VkLayerProperties> layers(count);
    if (vkEnumerateInstanceLayerProperties(&count, layers.data()) != VK_SUCCESS) return false;
    return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
        return std::strcmp(l.layerName, name) == 0;
    });
}

// Extensions of the implementation plus those a layer provides (layer may be null).
bool has_instance_extension(const char* layer, const char* name) {
    uint32_t count = 0;
    if (vkEnumerateInstanceExtensionProperties(layer, &count, nullptr) != VK_SUCCESS) return false;
    std::vector<VkExtensionProperties> exts(count);
    if (vkEnumerateInstanceExtensionProperties(layer, &count, exts.data()) != VK_SUCCESS)
        return false;
    return std::any_of(exts.begin(), exts.end(), [&](const VkExtensionProperties& e) {
        return std::strcmp(e.extensionName, name) == 0;
    });
}

const char* severity_name(VkDebugUtilsMessageSeverityFlagBitsEXT s) {
    if (s & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) return "error";
    if (s & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return "warning";
    if (s & VK_DEBUG_UTILS_MESSAGE_SEVERITY_INFO_BIT_EXT) return "info";
    return "verbose";
}

VKAPI_ATTR VkBool32 VKAPI_CALL on_debug_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                                const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                void* user) {
    auto* ctx = static_cast<Context*>(user);
    const char* id = data->pMessageIdName ? data->pMessageIdName : "(no id)";
    std::string text = fmt::format("[{}] {}: {}", severity_name(severity), id,
                                   data->pMessage ? data->pMessage : "");
    // The layer may call back from whichever thread made the Vulkan call.
    std::lock_guard<std::mutex> lock(ctx->messages_mutex);
    // The loader reports ICDs it could not load (intel/radeon without their hardware):
    // environment noise, not a fault of ours, but the explanation when no device is found.
    if (std::strcmp(id, "Loader Message") == 0)
        ctx->loader_messages.push_back(std::move(text));
    else
        ctx->messages.push_back(std::move(text));
    return VK_FALSE; // never make the layer fail the call: we want the real behaviour
}

VkDebugUtilsMessengerCreateInfoEXT messenger_info(Context* ctx) {
    VkDebugUtilsMessengerCreateInfoEXT info{};
    info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = on_debug_message;
    info.pUserData = ctx;
    return info;
}

} // namespace

uint32_t instance_api_version() {
    uint32_t loader_version = VK_API_VERSION_1_0;
    check(vkEnumerateInstanceVersion(&loader_version), "vkEnumerateInstanceVersion");
    if (loader_version < VK_API_VERSION_1_1)
        throw DeviceError(fmt::format("Vulkan loader supports only {}; 1.1 or newer is needed",
                                      format_api_version(loader_version)));
    // 1.2 is the newest core we use (driver properties); asking for more buys nothing.
    return std::min(loader_version, uint32_t{VK_API_VERSION_1_2});
}

InstanceLayers choose_layers(const DeviceOptions& options) {
    InstanceLayers out;
    // The loader implements debug utils itself, so a messenger also works without the
    // validation layer: then it only hears the loader, which explains device-less failures.
    const bool loader_debug_utils =
        has_instance_extension(nullptr, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    out.validation = options.validation && has_layer(kValidationLayer) &&
                     (loader_debug_utils ||
                      has_instance_extension(kValidationLayer, VK_EXT_DEBUG_UTILS_EXTENSION_NAME));
    out.messenger_wanted = out.validation || loader_debug_utils;
    if (out.validation) out.layers.push_back(kValidationLayer);
    if (out.messenger_wanted) out.extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    return out;
}

void create_instance(Context* ctx, const InstanceLayers& setup, uint32_t instance_api) {
    VkApplicationInfo app{};
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = "watergen";
    app.applicationVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
    app.pEngineName = "watergen-headless";
    app.engineVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
    app.apiVersion = instance_api;

    // Chained so that messages from vkCreateInstance / vkDestroyInstance are caught too.
    VkDebugUtilsMessengerCreateInfoEXT messenger = messenger_info(ctx);
    VkInstanceCreateInfo ici{};
    ici.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    ici.pNext = setup.messenger_wanted ? &messenger : nullptr;
    ici.pApplicationInfo = &app;
    ici.enabledLayerCount = static_cast<uint32_t>(setup.layers.size());
    ici.ppEnabledLayerNames = setup.layers.data();
    ici.enabledExtensionCount = static_cast<uint32_t>(setup.extensions.size());
    ici.ppEnabledExtensionNames = setup.extensions.data();
    VkResult r = vkCreateInstance(&ici, nullptr, &ctx->instance);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
        throw DeviceError(
            "no Vulkan driver could be loaded (vkCreateInstance failed: "
            "VK_ERROR_INCOMPATIBLE_DRIVER); install mesa-vulkan-drivers for lavapipe");
    check(r, "vkCreateInstance");

    if (setup.messenger_wanted) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(ctx->instance, "vkCreateDebugUtilsMessengerEXT"));
        ctx->destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(ctx->instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (!create || !ctx->destroy_messenger)
            throw DeviceError("vkGetInstanceProcAddr found no vkCreateDebugUtilsMessengerEXT");
        check(create(ctx->instance, &messenger, nullptr, &ctx->messenger),
              "vkCreateDebugUtilsMessengerEXT");
    }
}

} // namespace watergen::headless_detail
