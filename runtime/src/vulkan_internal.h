// Internals shared by the vulkan_*.cpp files of the runner. Not installed, not public.
//
// Inside the runner, failures throw RunnerError; VulkanRunner::render / run_compute catch
// everything at the API boundary and turn it into an error string. Every Vulkan object a
// job creates is registered with that job's Scope, which destroys them in reverse order.
#pragma once

#include "watergen/runtime/vulkan_runner.h"

#include <vulkan/vulkan.h>

#include <chrono>
#include <functional>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace watergen::vk_detail {

class RunnerError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

const char* result_name(VkResult r);

// Throws RunnerError("vkCall failed: VK_ERROR_...") unless r is VK_SUCCESS.
void vk_check(VkResult r, const char* call);

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

    // Set when a wait timed out or the device was lost: in-flight objects are leaked rather
    // than destroyed under the device's feet, and later jobs fail fast.
    bool unusable = false;

    mutable std::mutex messages_mutex;
    std::vector<std::string> messages;        // validation layer: what tests fail on
    std::vector<std::string> loader_messages; // loader (e.g. broken ICDs): for create errors

    Context() = default;
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;
    ~Context();
};

// Builds instance, picks the device, creates device/queue/pool. Throws RunnerError.
std::unique_ptr<Context> create_context(const RunnerOptions& options);

bool has_device_extension(VkPhysicalDevice pd, const char* name);

// ---- optional device features (vulkan_features.cpp) ----

// The features the runner enables when the device has them: 16-bit shader arithmetic and
// 16-bit storage-buffer access, so a half-precision probe can run in true binary16. The
// structs point at each other (pNext), so an instance stays where it was filled.
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
// stays off, as before), and records them in ctx->info. `api` is the version both the
// instance and the device support.
void choose_device_features(Context* ctx, uint32_t api, DeviceFeatures* out);

// Reverse-order destruction of everything a job created.
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

// ---- resources (vulkan_resources.cpp) ----

// Host-visible, persistently mapped buffer.
struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    void* mapped = nullptr;
    bool coherent = true;
};

Buffer create_buffer(Scope& scope, VkDeviceSize size, VkBufferUsageFlags usage);
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

// RGBA32F colour attachment that can be copied out.
Image create_color_target(Scope& scope, uint32_t width, uint32_t height);
// RGBA32F sampled texture (2D or cube), uploaded and left in SHADER_READ_ONLY_OPTIMAL.
Image create_texture(Scope& scope, const std::string& name, const TextureData& data, bool cube);

VkCommandBuffer allocate_command_buffer(Scope& scope);
VkFence create_fence(Scope& scope);
// Submits one command buffer and blocks until the fence signals (with a generous timeout).
void submit_and_wait(Context& ctx, VkCommandBuffer cmd, VkFence fence);
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

// ---- descriptors (vulkan_descriptors.cpp) ----

struct StageReflection {
    const Reflection* reflection;
    VkShaderStageFlags stage;
};

// What a job can feed into its descriptor bindings; null maps mean "none of that kind".
struct DescriptorInputs {
    const std::vector<uint8_t>* uniforms = nullptr;
    const std::map<std::string, TextureData>* textures = nullptr;
    TextureFilter filter = TextureFilter::Nearest;
    const std::map<std::string, std::vector<uint8_t>>* storage = nullptr;
    const std::map<std::string, uint64_t>* storage_sizes = nullptr;
};

struct BoundDescriptors {
    std::vector<VkDescriptorSetLayout> layouts; // index = set number, gaps are empty layouts
    std::vector<VkDescriptorSet> sets;
    std::map<std::string, Buffer> storage_buffers; // by binding name, for readback
};

// Union of the stages' bindings, layouts, pool, sets, and every resource they point at.
BoundDescriptors bind_descriptors(Scope& scope, const std::vector<StageReflection>& stages,
                                  const DescriptorInputs& inputs);

VkPipelineLayout create_pipeline_layout(Scope& scope, const BoundDescriptors& d);

// ---- timing ----

using Clock = std::chrono::steady_clock;
inline double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// ---- jobs (vulkan_render.cpp, vulkan_compute.cpp) ----

void render_job(Context& ctx, const RenderJob& job, RenderResult& result);
void render_jobs_interleaved(Context& ctx, const std::vector<RenderJob>& jobs, uint32_t rounds,
                             std::vector<RenderResult>& results);
void compute_job(Context& ctx, const ComputeJob& job, ComputeResult& result);

} // namespace watergen::vk_detail
