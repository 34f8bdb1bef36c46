// Instance, validation messenger, device selection (lavapipe unless told otherwise),
// logical device, queue and command pool.
#include "pipeline_state.h"
#include "vulkan_internal.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>

namespace watergen::vk_detail {
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

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

struct Candidate {
    VkPhysicalDevice device;
    VkPhysicalDeviceProperties props;
    VkPhysicalDeviceDriverProperties driver; // zeroed when the device cannot report it
};

Candidate describe(VkPhysicalDevice pd, uint32_t instance_api) {
    Candidate c{pd, {}, {}};
    vkGetPhysicalDeviceProperties(pd, &c.props);
    c.driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
    // Driver properties are core in 1.2 and an extension before; chaining the struct
    // otherwise is invalid usage.
    uint32_t api = std::min(instance_api, c.props.apiVersion);
    if (api >= VK_API_VERSION_1_2 ||
        has_device_extension(pd, VK_KHR_DRIVER_PROPERTIES_EXTENSION_NAME)) {
        VkPhysicalDeviceProperties2 props2{};
        props2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
        props2.pNext = &c.driver;
        vkGetPhysicalDeviceProperties2(pd, &props2);
    }
    return c;
}

std::string list_names(const std::vector<Candidate>& cs) {
    std::string out;
    for (const auto& c : cs) {
        if (!out.empty()) out += ", ";
        out += fmt::format("'{}'", c.props.deviceName);
    }
    return out.empty() ? "none" : out;
}

const Candidate& pick_device(const std::vector<Candidate>& cs, const RunnerOptions& options) {
    std::string wanted = options.device;
    const char* source = "RunnerOptions::device";
    if (wanted.empty()) {
        if (const char* env = std::getenv("WATERGEN_VK_DEVICE"); env && *env) {
            wanted = env;
            source = "WATERGEN_VK_DEVICE";
        }
    }
    if (!wanted.empty()) {
        for (const auto& c : cs)
            if (lower(c.props.deviceName).find(lower(wanted)) != std::string::npos) return c;
        throw RunnerError(fmt::format("no Vulkan device matches {}='{}' (devices: {})", source,
                                      wanted, list_names(cs)));
    }
    // lavapipe by driver ID first; any CPU device (an older or renamed software
    // rasterizer) second. Never a GPU by default: results must be reproducible.
    for (const auto& c : cs)
        if (c.driver.driverID == VK_DRIVER_ID_MESA_LLVMPIPE) return c;
    for (const auto& c : cs)
        if (c.props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) return c;
    throw RunnerError(
        fmt::format("no lavapipe (llvmpipe / CPU) Vulkan device found (devices: {}); install "
                    "mesa-vulkan-drivers or set WATERGEN_VK_DEVICE to a device name substring",
                    list_names(cs)));
}

// A family that can draw, dispatch and copy; prefer one that can write timestamps.
uint32_t pick_queue_family(VkPhysicalDevice pd, uint64_t* timestamp_mask) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, families.data());
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    int best = -1;
    for (uint32_t i = 0; i < count; ++i) {
        if ((families[i].queueFlags & need) != need) continue;
        if (best < 0 || (families[best].timestampValidBits == 0 && families[i].timestampValidBits))
            best = static_cast<int>(i);
    }
    if (best < 0) throw RunnerError("the Vulkan device has no graphics + compute queue family");
    uint32_t bits = families[best].timestampValidBits;
    *timestamp_mask = bits >= 64 ? ~uint64_t{0} : ((uint64_t{1} << bits) - 1);
    return static_cast<uint32_t>(best);
}

} // namespace

bool has_device_extension(VkPhysicalDevice pd, const char* name) {
    uint32_t count = 0;
    if (vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, nullptr) != VK_SUCCESS)
        return false;
    std::vector<VkExtensionProperties> exts(count);
    if (vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, exts.data()) != VK_SUCCESS)
        return false;
    return std::any_of(exts.begin(), exts.end(), [&](const VkExtensionProperties& e) {
        return std::strcmp(e.extensionName, name) == 0;
    });
}

Context::~Context() {
    // After a timeout the device may still be executing a job's commands; destroying the
    // device then is undefined behaviour, so leak instead (the process is usually exiting).
    if (unusable) return;
    if (device) {
        vkDeviceWaitIdle(device);
        if (command_pool) vkDestroyCommandPool(device, command_pool, nullptr);
        vkDestroyDevice(device, nullptr);
    }
    if (messenger && destroy_messenger) destroy_messenger(instance, messenger, nullptr);
    if (instance) vkDestroyInstance(instance, nullptr);
}

namespace {

// The newest instance API we use that the loader supports (1.1 at least).
uint32_t instance_api_version() {
    uint32_t loader_version = VK_API_VERSION_1_0;
    vk_check(vkEnumerateInstanceVersion(&loader_version), "vkEnumerateInstanceVersion");
    if (loader_version < VK_API_VERSION_1_1)
        throw RunnerError(fmt::format("Vulkan loader supports only {}; 1.1 or newer is needed",
                                      format_api_version(loader_version)));
    // 1.2 is the newest core we use (driver properties); asking for more buys nothing.
    return std::min(loader_version, uint32_t{VK_API_VERSION_1_2});
}

struct InstanceLayers {
    bool validation = false;
    bool messenger_wanted = false;
    std::vector<const char*> layers;
    std::vector<const char*> extensions;
};

InstanceLayers choose_layers(const RunnerOptions& options) {
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

// Creates ctx->instance and, when wanted, its debug messenger.
void create_instance(Context* ctx, const InstanceLayers& setup, uint32_t instance_api) {
    VkApplicationInfo app{};
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = "watergen";
    app.applicationVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
    app.pEngineName = "watergen-runner";
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
        throw RunnerError(
            "no Vulkan driver could be loaded (vkCreateInstance failed: "
            "VK_ERROR_INCOMPATIBLE_DRIVER); install mesa-vulkan-drivers for lavapipe");
    vk_check(r, "vkCreateInstance");

    if (setup.messenger_wanted) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(ctx->instance, "vkCreateDebugUtilsMessengerEXT"));
        ctx->destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(ctx->instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (!create || !ctx->destroy_messenger)
            throw RunnerError("vkGetInstanceProcAddr found no vkCreateDebugUtilsMessengerEXT");
        vk_check(create(ctx->instance, &messenger, nullptr, &ctx->messenger),
                 "vkCreateDebugUtilsMessengerEXT");
    }
}

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
    // Broken ICDs (e.g. intel/radeon with no matching hardware) are skipped by the loader;
    // only a failure of the whole enumeration is an error.
    // When every ICD fails, the loader returns VK_ERROR_INITIALIZATION_FAILED.
    const char* no_device = "no Vulkan physical device found (is mesa-vulkan-drivers installed? "
                            "does VK_ICD_FILENAMES / VK_DRIVER_FILES include lvp_icd?)";
    uint32_t count = 0;
    VkResult r = vkEnumeratePhysicalDevices(instance, &count, nullptr);
    if (r == VK_ERROR_INITIALIZATION_FAILED)
        throw RunnerError(
            fmt::format("{}; vkEnumeratePhysicalDevices failed: {}", no_device, result_name(r)));
    vk_check(r, "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> devices(count);
    r = vkEnumeratePhysicalDevices(instance, &count, devices.data());
    if (r != VK_INCOMPLETE) vk_check(r, "vkEnumeratePhysicalDevices");
    devices.resize(count);
    if (devices.empty()) throw RunnerError(no_device);
    return devices;
}

// Picks the device (options, else lavapipe) and records what it is in ctx.
void choose_physical_device(Context* ctx, const RunnerOptions& options, uint32_t instance_api,
                            bool validation) {
    std::vector<Candidate> candidates;
    for (VkPhysicalDevice pd : physical_devices(ctx->instance))
        candidates.push_back(describe(pd, instance_api));
    const Candidate& chosen = pick_device(candidates, options);
    if (chosen.props.apiVersion < VK_API_VERSION_1_1)
        throw RunnerError(fmt::format("Vulkan device '{}' supports only {}; 1.1 is needed",
                                      chosen.props.deviceName,
                                      format_api_version(chosen.props.apiVersion)));

    ctx->physical = chosen.device;
    ctx->limits = chosen.props.limits;
    vkGetPhysicalDeviceMemoryProperties(ctx->physical, &ctx->memory);
    ctx->info.name = chosen.props.deviceName;
    ctx->info.driver_name = chosen.driver.driverName;
    ctx->info.driver_info = chosen.driver.driverInfo;
    ctx->info.driver_version = chosen.props.driverVersion;
    ctx->info.api_version = chosen.props.apiVersion;
    ctx->info.validation_enabled = validation;
}

// Creates the logical device (with the optional features it has), its one queue and the
// command pool.
void create_device(Context* ctx, const std::vector<const char*>& layers, uint32_t instance_api) {
    DeviceFeatures features;
    choose_device_features(ctx, std::min(instance_api, ctx->info.api_version), &features);
    ctx->queue_family = pick_queue_family(ctx->physical, &ctx->timestamp_mask);
    vk_check(vk_state::create_device(ctx->physical, ctx->queue_family, &features.core,
                                     features.extensions, layers, &ctx->device),
             "vkCreateDevice");
    vkGetDeviceQueue(ctx->device, ctx->queue_family, 0, &ctx->queue);

    VkCommandPoolCreateInfo pci{};
    pci.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pci.queueFamilyIndex = ctx->queue_family;
    vk_check(vkCreateCommandPool(ctx->device, &pci, nullptr, &ctx->command_pool),
             "vkCreateCommandPool");
}

void build_context(Context* ctx, const RunnerOptions& options) {
    const uint32_t instance_api = instance_api_version();
    const InstanceLayers setup = choose_layers(options);
    create_instance(ctx, setup, instance_api);
    choose_physical_device(ctx, options, instance_api, setup.validation);
    create_device(ctx, setup.layers, instance_api);
}

} // namespace

std::unique_ptr<Context> create_context(const RunnerOptions& options) {
    auto ctx = std::make_unique<Context>();
    try {
        build_context(ctx.get(), options);
    } catch (const RunnerError& e) {
        // Creation failed: what the loader said about unloadable drivers is the likely
        // explanation, so it goes into the one error message.
        std::string text = e.what();
        for (const std::string& m : ctx->loader_messages)
            text += "\n  loader: " + m;
        throw RunnerError(text);
    }
    // Loader notes from a successful start (e.g. the intel/radeon ICDs skipped on a
    // machine without that hardware) are not worth keeping.
    ctx->loader_messages.clear();
    return ctx;
}

} // namespace watergen::vk_detail
