// Device selection (lavapipe unless told otherwise), the logical device with the features it
// has, its queue and command pool; the whole context built in order (the instance:
// device_instance.cpp).
#include "device_context.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>

namespace watergen::headless_detail {
namespace {

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

const Candidate& pick_device(const std::vector<Candidate>& cs, const DeviceOptions& options) {
    std::string wanted = options.device;
    const char* source = "DeviceOptions::device";
    if (wanted.empty()) {
        if (const char* env = std::getenv("WATERGEN_VK_DEVICE"); env && *env) {
            wanted = env;
            source = "WATERGEN_VK_DEVICE";
        }
    }
    if (!wanted.empty()) {
        for (const auto& c : cs)
            if (lower(c.props.deviceName).find(lower(wanted)) != std::string::npos) return c;
        throw DeviceError(fmt::format("no Vulkan device matches {}='{}' (devices: {})", source,
                                      wanted, list_names(cs)));
    }
    // lavapipe by driver ID first; any CPU device (an older or renamed software
    // rasterizer) second. Never a GPU by default: results must be reproducible.
    for (const auto& c : cs)
        if (c.driver.driverID == VK_DRIVER_ID_MESA_LLVMPIPE) return c;
    for (const auto& c : cs)
        if (c.props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) return c;
    throw DeviceError(
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
    if (best < 0) throw DeviceError("the Vulkan device has no graphics + compute queue family");
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
        for (const auto& [format, pass] : render_passes)
            vkDestroyRenderPass(device, pass, nullptr);
        if (command_pool) vkDestroyCommandPool(device, command_pool, nullptr);
        vkDestroyDevice(device, nullptr);
    }
    if (messenger && destroy_messenger) destroy_messenger(instance, messenger, nullptr);
    if (instance) vkDestroyInstance(instance, nullptr);
}

namespace {

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
    // Broken ICDs (e.g. intel/radeon with no matching hardware) are skipped by the loader;
    // only a failure of the whole enumeration is an error.
    // When every ICD fails, the loader returns VK_ERROR_INITIALIZATION_FAILED.
    const char* no_device = "no Vulkan physical device found (is mesa-vulkan-drivers installed? "
                            "does VK_ICD_FILENAMES / VK_DRIVER_FILES include lvp_icd?)";
    uint32_t count = 0;
    VkResult r = vkEnumeratePhysicalDevices(instance, &count, nullptr);
    if (r == VK_ERROR_INITIALIZATION_FAILED)
        throw DeviceError(
            fmt::format("{}; vkEnumeratePhysicalDevices failed: {}", no_device, result_name(r)));
    check(r, "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> devices(count);
    r = vkEnumeratePhysicalDevices(instance, &count, devices.data());
    if (r != VK_INCOMPLETE) check(r, "vkEnumeratePhysicalDevices");
    devices.resize(count);
    if (devices.empty()) throw DeviceError(no_device);
    return devices;
}

// Picks the device (options, else lavapipe) and records what it is in ctx.
void choose_physical_device(Context* ctx, const DeviceOptions& options, uint32_t instance_api,
                            bool validation) {
    std::vector<Candidate> candidates;
    for (VkPhysicalDevice pd : physical_devices(ctx->instance))
        candidates.push_back(describe(pd, instance_api));
    const Candidate& chosen = pick_device(candidates, options);
    if (chosen.props.apiVersion < VK_API_VERSION_1_1)
        throw DeviceError(fmt::format("Vulkan device '{}' supports only {}; 1.1 is needed",
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
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{};
    qci.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    qci.queueFamilyIndex = ctx->queue_family;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    VkDeviceCreateInfo dci{};
    dci.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    dci.pNext = &features.core; // VkPhysicalDeviceFeatures2 in place of pEnabledFeatures
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.enabledExtensionCount = static_cast<uint32_t>(features.extensions.size());
    dci.ppEnabledExtensionNames = features.extensions.data();
    // Device layers are deprecated and ignored by current loaders; set for old ones.
    dci.enabledLayerCount = static_cast<uint32_t>(layers.size());
    dci.ppEnabledLayerNames = layers.data();
    check(vkCreateDevice(ctx->physical, &dci, nullptr, &ctx->device), "vkCreateDevice");
    vkGetDeviceQueue(ctx->device, ctx->queue_family, 0, &ctx->queue);

    VkCommandPoolCreateInfo pci{};
    pci.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pci.queueFamilyIndex = ctx->queue_family;
    check(vkCreateCommandPool(ctx->device, &pci, nullptr, &ctx->command_pool),
          "vkCreateCommandPool");
}

void build_context(Context* ctx, const DeviceOptions& options) {
    const uint32_t instance_api = instance_api_version();
    const InstanceLayers setup = choose_layers(options);
    create_instance(ctx, setup, instance_api);
    choose_physical_device(ctx, options, instance_api, setup.validation);
    create_device(ctx, setup.layers, instance_api);
    // The water's target, which HeadlessDevice::render_pass() hands out without a failure.
    ctx->render_passes[VK_FORMAT_R32G32B32A32_SFLOAT] =
        create_offscreen_render_pass(*ctx, VK_FORMAT_R32G32B32A32_SFLOAT);
}

} // namespace

std::unique_ptr<Context> create_context(const DeviceOptions& options) {
    auto ctx = std::make_unique<Context>();
    try {
        build_context(ctx.get(), options);
    } catch (const DeviceError& e) {
        // Creation failed: what the loader said about unloadable drivers is the likely
        // explanation, so it goes into the one error message.
        std::string text = e.what();
        for (const std::string& m : ctx->loader_messages)
            text += "\n  loader: " + m;
        throw DeviceError(text);
    }
    // Loader notes from a successful start (e.g. the intel/radeon ICDs skipped on a
    // machine without that hardware) are not worth keeping.
    ctx->loader_messages.clear();
    return ctx;
}

} // namespace watergen::headless_detail
