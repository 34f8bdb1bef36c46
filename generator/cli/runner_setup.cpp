#include <cstdlib>
#include <filesystem>

#include "commands.h"

namespace watergen::cli {

void add_runner_options(CLI::App& app, RunnerSetup& setup) {
    app.add_option("--shader-cache", setup.shader_cache,
                   "Mesa shader cache: 'off' (default: every pipeline is JIT-compiled afresh, so "
                   "first-draw times "
                   "are honest) or a directory of its own");
    app.add_option("--device", setup.device,
                   "Vulkan device name substring (default: lavapipe / llvmpipe)");
}

std::unique_ptr<VulkanRunner> create_runner(const RunnerSetup& setup, std::string* cache_used) {
    // Mesa reads these when the device is created, so they are set before.
    if (setup.shader_cache == "off") {
        ::setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);
        *cache_used = "disabled";
    } else {
        std::filesystem::create_directories(setup.shader_cache);
        ::setenv("MESA_SHADER_CACHE_DIR", setup.shader_cache.c_str(), 1);
        ::unsetenv("MESA_SHADER_CACHE_DISABLE");
        *cache_used = setup.shader_cache;
    }
    std::string error;
    DeviceOptions options;
    options.device = setup.device;
    options.validation = false; // commands measure; the tests run with validation on
    auto runner = VulkanRunner::create(options, &error);
    if (!runner)
        std::fprintf(
            stderr,
            "watergen: error: no Vulkan device: %s (install mesa-vulkan-drivers for lavapipe)\n",
            error.c_str());
    return runner;
}

} // namespace watergen::cli
