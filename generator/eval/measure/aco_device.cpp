#include "watergen/eval/measure/aco_device.h"

#include <fmt/format.h>

#include <cstring>
#include <map>

#include <vulkan/vulkan.h>

#include "watergen/toolchain/spirv_tools_stage.h"

namespace watergen {

struct AcoDevice::Handles {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    std::map<VkFormat, VkRenderPass> render_passes; // one per target format, made when needed
    PFN_vkGetPipelineExecutablePropertiesKHR properties = nullptr;
    PFN_vkGetPipelineExecutableStatisticsKHR statistics = nullptr;
    PFN_vkGetPipelineExecutableInternalRepresentationsKHR representations = nullptr;
};

namespace {

std::string failed(const char* call, VkResult r) {
    return fmt::format("{} failed (VkResult {})", call, static_cast<int>(r));
}

bool has_extension(VkPhysicalDevice pd, const char* name) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> exts(count);
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, exts.data());
    for (const auto& e : exts)
        if (std::strcmp(e.extensionName, name) == 0) return true;
    return false;
}

// The first RADV device the loader lists (with only radeon's ICD, the null device).
VkPhysicalDevice find_radv(VkInstance instance, std::string* name, std::string* info) {
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance, &count, devices.data());
    for (VkPhysicalDevice pd : devices) {
        VkPhysicalDeviceDriverProperties driver{};
        driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
        VkPhysicalDeviceProperties2 props{};
        props.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
        props.pNext = &driver;
        vkGetPhysicalDeviceProperties2(pd, &props);
        if (driver.driverID != VK_DRIVER_ID_MESA_RADV) continue;
        *name = props.properties.deviceName;
        *info = driver.driverInfo;
        return pd;
    }
    return VK_NULL_HANDLE;
}

// The water pass draws into RGBA16F, an engine's HDR target: the export instructions are those
// it pays for there.
VkRenderPass make_render_pass(VkDevice device, VkFormat format, std::string* error) {
    VkAttachmentDescription colour{};
    colour.format = format;
    colour.samples = VK_SAMPLE_COUNT_1_BIT;
    colour.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    colour.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    colour.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    colour.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    colour.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;
    VkRenderPassCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
    info.attachmentCount = 1;
    info.pAttachments = &colour;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    VkRenderPass pass = VK_NULL_HANDLE;
    const VkResult r = vkCreateRenderPass(device, &info, nullptr, &pass);
    if (r != VK_SUCCESS) *error = failed("vkCreateRenderPass", r);
    return pass;
}

const char* stage_name(VkShaderStageFlags stages) {
    if (stages & VK_SHADER_STAGE_VERTEX_BIT) return "vertex";
    if (stages & VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT) return "tess_control";
    if (stages & VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT) return "tess_evaluation";
    if (stages & VK_SHADER_STAGE_GEOMETRY_BIT) return "vertex";
    if (stages & VK_SHADER_STAGE_FRAGMENT_BIT) return "fragment";
    return "other";
}

double statistic_value(const VkPipelineExecutableStatisticKHR& s) {
    switch (s.format) {
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR:
        return s.value.b32 ? 1.0 : 0.0;
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR:
        return static_cast<double>(s.value.i64);
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR:
        return static_cast<double>(s.value.u64);
    default:
        return s.value.f64;
    }
}

// The executable's "Assembly" representation (ACO's disassembly), "" without one.
std::string disassembly(const AcoDevice::Handles& h, VkPipelineExecutableInfoKHR info) {
    uint32_t count = 0;
    if (h.representations(h.device, &info, &count, nullptr) != VK_SUCCESS) return "";
    std::vector<VkPipelineExecutableInternalRepresentationKHR> reps(count);
    for (auto& r : reps)
        r.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INTERNAL_REPRESENTATION_KHR;
    if (h.representations(h.device, &info, &count, reps.data()) != VK_SUCCESS) return "";
    std::vector<std::string> texts(count);
    for (uint32_t i = 0; i < count; ++i) {
        texts[i].resize(reps[i].dataSize);
        reps[i].pData = texts[i].data();
    }
    if (h.representations(h.device, &info, &count, reps.data()) != VK_SUCCESS) return "";
    for (uint32_t i = 0; i < count; ++i)
        if (std::strcmp(reps[i].name, "Assembly") == 0)
            return std::string(texts[i].c_str()); // dataSize counts the terminating NUL
    return "";
}

AcoStageStatistics read_executable(const AcoDevice::Handles& h, VkPipeline pipeline, uint32_t i,
                                   const VkPipelineExecutablePropertiesKHR& props,
                                   bool want_disassembly) {
    AcoStageStatistics out;
    out.stage = stage_name(props.stages);
    out.executable = props.name;
    out.subgroup_size = props.subgroupSize;
    VkPipelineExecutableInfoKHR info{};
    info.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR;
    info.pipeline = pipeline;
    info.executableIndex = i;
    uint32_t count = 0;
    if (h.statistics(h.device, &info, &count, nullptr) == VK_SUCCESS) {
        std::vector<VkPipelineExecutableStatisticKHR> stats(count);
        for (auto& s : stats)
            s.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR;
        if (h.statistics(h.device, &info, &count, stats.data()) == VK_SUCCESS)
            for (const auto& s : stats)
                out.values[s.name] = statistic_value(s);
    }
    const std::string text = want_disassembly ? disassembly(h, info) : std::string();
    if (!text.empty()) {
        std::string error;
        if (auto listing = read_aco_listing(text, &error)) {
            out.loops = std::move(listing->loops);
            out.has_disassembly = true;
        }
    }
    return out;
}

} // namespace

double AcoStageStatistics::value(const std::string& name) const {
    const auto it = values.find(name);
    return it == values.end() ? -1.0 : it->second;
}

std::unique_ptr<AcoDevice> AcoDevice::open(std::string* error, bool disassembly) {
    std::unique_ptr<AcoDevice> d(new AcoDevice);
    d->disassembly_ = disassembly;
    d->h_ = std::make_unique<Handles>();
    Handles& h = *d->h_;
    VkApplicationInfo app{};
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = "watergen";
    app.apiVersion = VK_API_VERSION_1_2;
    VkInstanceCreateInfo ici{};
    ici.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    ici.pApplicationInfo = &app;
    VkResult r = vkCreateInstance(&ici, nullptr, &h.instance);
    if (r != VK_SUCCESS) {
        *error = failed("vkCreateInstance", r);
        return nullptr;
    }
    h.physical = find_radv(h.instance, &d->name_, &d->info_);
    if (!h.physical) {
        *error = "the Vulkan loader lists no RADV device (mesa-vulkan-drivers' radeon_icd, "
                 "with RADV_FORCE_FAMILY naming a family for its null device)";
        return nullptr;
    }
    if (!has_extension(h.physical, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME)) {
        *error = d->name_ + " has no VK_KHR_pipeline_executable_properties";
        return nullptr;
    }
    // The 16-bit features a strict-half shader declares, where the family has them.
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR exec{};
    exec.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR;
    VkPhysicalDeviceVulkan12Features v12{};
    v12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
    v12.pNext = &exec;
    VkPhysicalDeviceVulkan11Features v11{};
    v11.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES;
    v11.pNext = &v12;
    VkPhysicalDeviceFeatures2 supported{};
    supported.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
    supported.pNext = &v11;
    vkGetPhysicalDeviceFeatures2(h.physical, &supported);
    VkPhysicalDeviceVulkan12Features want12{};
    want12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
    want12.pNext = &exec;
    want12.shaderFloat16 = v12.shaderFloat16;
    d->float16_ = v12.shaderFloat16 == VK_TRUE;
    VkPhysicalDeviceVulkan11Features want11{};
    want11.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES;
    want11.pNext = &want12;
    want11.storageBuffer16BitAccess = v11.storageBuffer16BitAccess;
    want11.uniformAndStorageBuffer16BitAccess = v11.uniformAndStorageBuffer16BitAccess;
    VkPhysicalDeviceFeatures2 want{};
    want.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
    want.pNext = &want11;
    want.features.shaderInt16 = supported.features.shaderInt16;
    want.features.tessellationShader = supported.features.tessellationShader; // mesh variants
    exec.pipelineExecutableInfo = VK_TRUE;

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{};
    queue.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    queue.queueFamilyIndex = 0;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    const char* extensions[] = {VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME};
    VkDeviceCreateInfo dci{};
    dci.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    dci.pNext = &want;
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &queue;
    dci.enabledExtensionCount = 1;
    dci.ppEnabledExtensionNames = extensions;
    r = vkCreateDevice(h.physical, &dci, nullptr, &h.device);
    if (r != VK_SUCCESS) {
        *error = d->name_ + ": " + failed("vkCreateDevice", r);
        return nullptr;
    }
    h.properties = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
        vkGetDeviceProcAddr(h.device, "vkGetPipelineExecutablePropertiesKHR"));
    h.statistics = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
        vkGetDeviceProcAddr(h.device, "vkGetPipelineExecutableStatisticsKHR"));
    h.representations = reinterpret_cast<PFN_vkGetPipelineExecutableInternalRepresentationsKHR>(
        vkGetDeviceProcAddr(h.device, "vkGetPipelineExecutableInternalRepresentationsKHR"));
    if (!h.properties || !h.statistics || !h.representations) {
        *error = d->name_ + ": the pipeline executable entry points are missing";
        return nullptr;
    }
    return d;
}

AcoDevice::~AcoDevice() {
    if (!h_) return;
    for (const auto& [format, pass] : h_->render_passes)
        vkDestroyRenderPass(h_->device, pass, nullptr);
    if (h_->device) vkDestroyDevice(h_->device, nullptr);
    if (h_->instance) vkDestroyInstance(h_->instance, nullptr);
}

AcoPipelineStatistics AcoDevice::compile(const AcoPipelineSource& source) {
    AcoPipelineStatistics out;
    out.name = source.name;
    // Creating it anyway would be invalid usage, and ACO for gfx6 aborts on 16-bit arithmetic.
    const bool float16 = declares_capability(source.vertex, kCapabilityFloat16) ||
                         declares_capability(source.fragment, kCapabilityFloat16) ||
                         declares_capability(source.tess_control, kCapabilityFloat16) ||
                         declares_capability(source.tess_evaluation, kCapabilityFloat16);
    if (!float16_ && float16) {
        out.unsupported = true;
        out.error =
            name_ + " has no shaderFloat16: the shader's 16-bit arithmetic cannot run there";
        return out;
    }
    VariantPipelineDesc desc;
    desc.vertex_spirv = &source.vertex;
    desc.fragment_spirv = &source.fragment;
    desc.vertex_reflection = &source.vertex_reflection;
    desc.fragment_reflection = &source.fragment_reflection;
    if (!source.tess_control.empty()) {
        desc.tess_control_spirv = &source.tess_control;
        desc.tess_evaluation_spirv = &source.tess_evaluation;
        desc.tess_control_reflection = &source.tess_control_reflection;
        desc.tess_evaluation_reflection = &source.tess_evaluation_reflection;
    }
    // A value that is no colour format (a depth format, or none at all) never reaches the
    // driver, and the device must render to the one it is.
    VkFormatProperties format{};
    if (is_colour_format(source.format))
        vkGetPhysicalDeviceFormatProperties(h_->physical, source.format, &format);
    if (!(format.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT)) {
        out.error = name_ + " cannot render to format " +
                    std::to_string(static_cast<int64_t>(source.format)) +
                    " (VkFormat): expected a colour format it renders to";
        return out;
    }
    VkRenderPass& pass = h_->render_passes[source.format];
    if (!pass) pass = make_render_pass(h_->device, source.format, &out.error);
    if (!pass) return out;
    desc.render_pass = pass;
    desc.specialization = source.specialization;
    desc.flags = VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR |
                 (disassembly_ ? VK_PIPELINE_CREATE_CAPTURE_INTERNAL_REPRESENTATIONS_BIT_KHR : 0);
    auto pipeline = source.geometry
                        ? VariantPipeline::create(h_->device, desc, *source.geometry, &out.error)
                        : VariantPipeline::create(h_->device, desc, &out.error);
    if (!pipeline) return out;
    VkPipelineInfoKHR info{};
    info.sType = VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR;
    info.pipeline = pipeline->pipeline();
    uint32_t count = 0;
    VkResult r = h_->properties(h_->device, &info, &count, nullptr);
    std::vector<VkPipelineExecutablePropertiesKHR> props(count);
    for (auto& p : props)
        p.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR;
    if (r == VK_SUCCESS) r = h_->properties(h_->device, &info, &count, props.data());
    if (r != VK_SUCCESS) {
        out.error = failed("vkGetPipelineExecutablePropertiesKHR", r);
        return out;
    }
    for (uint32_t i = 0; i < count; ++i)
        out.stages.push_back(read_executable(*h_, pipeline->pipeline(), i, props[i], disassembly_));
    return out;
}

} // namespace watergen
