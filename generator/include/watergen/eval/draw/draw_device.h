// The device the commands draw and measure on: lavapipe (or the named device) without the
// validation layers (commands measure; the tests run with them on), and Mesa's shader cache off
// (every pipeline JIT-compiled afresh, so first-draw times are honest) or in a directory of its
// own. And how a command's run ended, for its exit code.
#pragma once

#include <memory>
#include <string>

#include "watergen/runner/vulkan_runner.h"

namespace watergen {

struct DrawDeviceChoice {
    std::string shader_cache = "off"; // "off" or a directory
    std::string device;               // device name substring; "": lavapipe / llvmpipe
};

// What:   applies the shader-cache choice to this process's environment (Mesa reads it when
//         the device is created; *cache_used: "disabled" or the directory) and creates the
//         runner.
// Output: the runner, or nullptr and in *error "no Vulkan device: <why> (install ...)".
std::unique_ptr<VulkanRunner> open_draw_device(const DrawDeviceChoice& choice,
                                               std::string* cache_used, std::string* error);

// Why a run stopped: bad input (exit 2), a failure of the work (exit 1), no device (exit 3).
enum class RunStatus { Ok, BadInput, Failed, NoDevice };

} // namespace watergen
