// Internals of the headless device (watergen_headless), shared by its .cpp files. Not installed.
//
// The error model: inside the device a failure throws DeviceError (check() for a VkResult);
// every public entry point runs its body under guarded(), which catches everything (also
// std::bad_alloc) and hands the message back as data. Every Vulkan object a draw or dispatch
// creates is registered with its Scope, which destroys them in reverse order.
#pragma once

#include "watergen/headless/headless_device.h"

#include <vulkan/vulkan.h>

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace watergen::headless_detail {

class DeviceError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// "VK_ERROR_DEVICE_LOST"; null for a value Vulkan 1.3 core and our extensions do not return.
const char* result_name(VkResult r);

// Throws DeviceError("vkCall failed: VK_ERROR_...") unless r is VK_SUCCESS.
void check(VkResult r, const char* call);

struct Context {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    PFN_vkDestroyDebugUtilsMessengerEXT destroy_messenger = nullptr;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    VkCommandPool command_pool = VK_NULL_HANDLE;
    VkPhysicalDeviceMemoryProperties memory{};
    VkPhysicalDeviceLimits limits{};
    uint64_t timestamp_mask = 0; // from the queue family's timestampValidBits
    DeviceInfo info;
    // HeadlessDevice::render_pass(): one per target format, made on first use.
    std::map<VkFormat, VkRenderPass> render_passes;

    // Set when a wait timed out or the device was lost: in-flight objects are leaked rather
    // than destroyed under the device's feet, and later calls fail fast.
    bool unusable = false;

    mutable std::mutex messages_mutex;
    std::vector<std::string> messages;        // validation layer: what tests fail on
    std::vector<std::string> loader_messages; // loader (e.g. broken ICDs): for create errors

    Context() = default;
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;
    ~Context();
};

// ---- creation (device_instance.cpp, device_choice.cpp, device_features.cpp) ----

// The instance layers and extensions chosen from the options and what is installed.
struct InstanceLayers {
    bool validation = false;
    bool messenger_wanted = false;
    std::vector<const char*> layers;
    std::vector<const char*> extensions;
};

InstanceLayers choose_layers(const DeviceOptions& options);
// The newest instance API we use that the loader supports (1.1 at least).
uint32_t instance_api_version();
// Creates ctx->instance and, when wanted, its debug messenger (messages go to ctx).
void create_instance(Context* ctx, const InstanceLayers& setup, uint32_t instance_api);

// Builds instance, picks the device, creates device, queue, pool and the RGBA32F render pass.
std::unique_ptr<Context> create_context(const DeviceOptions& options);

bool has_device_extension(VkPhysicalDevice pd, const char* name);

// The features the device enables when it has them: 16-bit shader arithmetic and 16-bit
// storage-buffer access, so a half-precision probe can run in true binary16. The structs point
// at each other (pNext), so an instance stays where it was filled.
struct DeviceFeatures {
    VkPhysicalDeviceFeatures2 core{};
    VkPhysicalDevice16BitStorageFeatures storage16{};
    VkPhysicalDeviceShaderFloat16Int8Features float16_int8{};
    std::vector<const char*> extensions; // device extensions the chain needs (before 1.2)
    DeviceFeatures() = default;
    DeviceFeatures(const DeviceFeatures&) = delete;
    DeviceFeatures& operator=(const DeviceFeatures&) = delete;
};

// Queries ctx->physical, keeps only the wanted features it supports (every other feature
// stays off), and records them in ctx->info. `api` is the version both the instance and the
// device support.
void choose_device_features(Context* ctx, uint32_t api, DeviceFeatures* out);

// One colour attachment of `format`, cleared, left in TRANSFER_SRC_OPTIMAL for the copy out.
VkRenderPass create_offscreen_render_pass(Context& ctx, VkFormat format);

// ---- the API boundary ----

// Runs `body` unless the device is unusable; false and `*error` (when given) set to what
// failed if anything throws.
template <typename Body> bool guarded(const Context& ctx, std::string* error, Body&& body) {
    try {
        if (ctx.unusable)
            throw DeviceError(
                "the Vulkan device is unusable after an earlier timeout or device loss");
        body();
        return true;
    } catch (const std::exception& e) {
        if (error) *error = e.what();
    } catch (...) {
        if (error) *error = "unknown failure in the headless device";
    }
    return false;
}

// ---- objects of one draw or dispatch ----

// Reverse-order destruction of everything a draw or dispatch created.
class Scope {
  public:
    explicit Scope(Context& ctx) : ctx_(ctx) {}
    ~Scope();
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;
    void defer(std::function<void()> destroy) { cleanups_.push_back(std::move(destroy)); }
    Context& ctx() { return ctx_; }

  private:
    Context& ctx_;
    std::vector<std::function<void()>> cleanups_;
};

using Clock = std::chrono::steady_clock;
inline double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

} // namespace watergen::headless_detail
