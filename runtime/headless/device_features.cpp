// Optional device features: 16-bit shader arithmetic and 16-bit storage. lavapipe (Mesa 22.3)
// has them; enabling them lets a probe run float16_t arithmetic in true binary16 instead of
// the 32-bit "mediump" hint (watergen issue 14). Tessellation shaders, for the tessellated mesh
// path (issue 28): lavapipe has them too, up to level 64.
#include "device_context.h"

namespace watergen::headless_detail {
namespace {

// Whether the float16 / int8 feature struct may be chained: core in 1.2, an extension before.
bool float16_int8_known(VkPhysicalDevice pd, uint32_t api, std::vector<const char*>* extensions) {
    if (api >= VK_API_VERSION_1_2) return true;
    if (!has_device_extension(pd, VK_KHR_SHADER_FLOAT16_INT8_EXTENSION_NAME)) return false;
    extensions->push_back(VK_KHR_SHADER_FLOAT16_INT8_EXTENSION_NAME);
    return true;
}

// Float controls are core in 1.2 and an extension before; the property tells whether
// binary16 subnormals survive arithmetic (else they may be flushed to zero).
bool float16_denorms_preserved(VkPhysicalDevice pd, uint32_t api) {
    if (api < VK_API_VERSION_1_2 &&
        !has_device_extension(pd, VK_KHR_SHADER_FLOAT_CONTROLS_EXTENSION_NAME))
        return false;
    VkPhysicalDeviceFloatControlsProperties controls{};
    controls.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FLOAT_CONTROLS_PROPERTIES;
    VkPhysicalDeviceProperties2 props{};
    props.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
    props.pNext = &controls;
    vkGetPhysicalDeviceProperties2(pd, &props);
    return controls.shaderDenormPreserveFloat16 == VK_TRUE;
}

} // namespace

void choose_device_features(Context* ctx, uint32_t api, DeviceFeatures* out) {
    out->core.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
    out->storage16.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_16BIT_STORAGE_FEATURES;
    out->float16_int8.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_FLOAT16_INT8_FEATURES;
    out->core.pNext = &out->storage16; // 16-bit storage is core in 1.1, the device's minimum
    if (float16_int8_known(ctx->physical, api, &out->extensions))
        out->storage16.pNext = &out->float16_int8;
    vkGetPhysicalDeviceFeatures2(ctx->physical, &out->core);

    // Keep only what we want: every other feature stays disabled, as it always was.
    const VkPhysicalDeviceFeatures supported = out->core.features;
    out->core.features = VkPhysicalDeviceFeatures{};
    out->core.features.shaderInt16 = supported.shaderInt16;
    out->core.features.tessellationShader = supported.tessellationShader;
    const VkPhysicalDevice16BitStorageFeatures storage = out->storage16;
    out->storage16 = VkPhysicalDevice16BitStorageFeatures{};
    out->storage16.sType = storage.sType;
    out->storage16.pNext = storage.pNext;
    out->storage16.storageBuffer16BitAccess = storage.storageBuffer16BitAccess;
    out->storage16.uniformAndStorageBuffer16BitAccess = storage.uniformAndStorageBuffer16BitAccess;
    out->float16_int8.shaderInt8 = VK_FALSE;

    DeviceInfo& info = ctx->info;
    info.shader_float16 = out->float16_int8.shaderFloat16 == VK_TRUE;
    info.shader_int16 = out->core.features.shaderInt16 == VK_TRUE;
    info.storage_buffer_16bit = out->storage16.storageBuffer16BitAccess == VK_TRUE;
    info.uniform_storage_16bit = out->storage16.uniformAndStorageBuffer16BitAccess == VK_TRUE;
    info.float16_denorms_preserved = float16_denorms_preserved(ctx->physical, api);
    info.tessellation_shader = out->core.features.tessellationShader == VK_TRUE;
    if (info.tessellation_shader) {
        VkPhysicalDeviceProperties props{};
        vkGetPhysicalDeviceProperties(ctx->physical, &props);
        info.max_tessellation_level = props.limits.maxTessellationGenerationLevel;
    }
}

} // namespace watergen::headless_detail
