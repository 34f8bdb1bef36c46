#include <cstdio>

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
    std::string error;
    auto runner = open_draw_device(setup, cache_used, &error);
    if (!runner) std::fprintf(stderr, "watergen: error: %s\n", error.c_str());
    return runner;
}

bool has_float16(const VulkanRunner& runner, const char* why) {
    if (runner.device_info().shader_float16) return true;
    std::fprintf(stderr, "watergen: error: %s has no shaderFloat16%s\n",
                 runner.device_info().name.c_str(), why);
    return false;
}

} // namespace watergen::cli
