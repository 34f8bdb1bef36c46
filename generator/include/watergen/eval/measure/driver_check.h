// Every pipeline of a build through real GPU compilers: `watergen build --check-drivers`. Each
// variant's GLSL and HLSL paths (and each companion pass once) as an engine creates them from
// the output directory (runtime's ShaderBuild: the optimised or frozen SPIR-V, the reflection,
// the selector values of a specialized build), compiled by ACO on each family's null device.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "watergen/eval/measure/aco_worker.h"

namespace watergen {

struct DriverCheck {
    size_t pipelines = 0;              // per family
    std::vector<std::string> failures; // "<target>: <scene>/<key> <lang>: what the driver said"
    std::string error;                 // the build could not be read
    bool no_device = false;            // a family's null device is missing (exit 3)
    bool ok() const { return error.empty() && failures.empty(); }
};

// What:   the check of the build in `build_dir` on `targets`, AMD families only (lavapipe,
//         which renders every variant in the tests already, or an empty list is an error, not
//         a check that passed). A worker that crashed names the pipeline it was compiling.
// Cost:   2-20 ms per pipeline and family, the families in parallel.
DriverCheck check_build_on_drivers(const std::filesystem::path& build_dir,
                                   const std::vector<GpuTarget>& targets,
                                   const std::filesystem::path& scratch,
                                   const std::filesystem::path& worker = own_executable());

} // namespace watergen
