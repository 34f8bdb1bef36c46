#include "watergen/eval/draw/draw_device.h"

#include <cstdlib>
#include <filesystem>

namespace watergen {

std::unique_ptr<VulkanRunner> open_draw_device(const DrawDeviceChoice& choice,
                                               std::string* cache_used, std::string* error) {
    // Mesa reads these when the device is created, so they are set before.
    if (choice.shader_cache == "off") {
        ::setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);
        *cache_used = "disabled";
    } else {
        std::filesystem::create_directories(choice.shader_cache);
        ::setenv("MESA_SHADER_CACHE_DIR", choice.shader_cache.c_str(), 1);
        ::unsetenv("MESA_SHADER_CACHE_DISABLE");
        *cache_used = choice.shader_cache;
    }
    DeviceOptions options;
    options.device = choice.device;
    options.validation = false; // commands measure; the tests run with validation on
    std::string why;
    auto runner = VulkanRunner::create(options, &why);
    if (!runner)
        *error = "no Vulkan device: " + why + " (install mesa-vulkan-drivers for lavapipe)";
    return runner;
}

} // namespace watergen
