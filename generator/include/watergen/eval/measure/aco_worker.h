// ACO statistics from a child process: the `watergen` executable run again as a hidden worker
// (`watergen gpu-worker DIR`) with the loader pointed at RADV's ICD alone and RADV_FORCE_FAMILY
// set, so a family radv does not know (it aborts), a compiler crash or a hang takes the worker
// down and not the command. This file owns both sides of the protocol: the job directory
// (DIR/job.json and the pipelines' SPIR-V and reflection beside it) and its answer
// (DIR/result.json, written atomically by the worker).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "watergen/eval/measure/aco_device.h"
#include "watergen/eval/measure/aco_job.h"
#include "watergen/eval/measure/cost_worker.h"
#include "watergen/eval/measure/gpu_target.h"

namespace watergen {

// The radeon ICD manifest mesa-vulkan-drivers installs (radeon_icd.<arch>.json in the loader's
// system directories), or the file the environment variable WATERGEN_RADEON_ICD names (a Mesa
// installed elsewhere); nullopt when there is none.
std::optional<std::filesystem::path> radeon_icd();

struct AcoTargetRun {
    GpuTarget target;
    std::string device, driver;                   // "AMD RADV NAVI21", "Mesa 22.3.6 (LLVM 15.0.6)"
    std::vector<AcoPipelineStatistics> pipelines; // in the order of the sources
    std::string error;                            // the worker failed as a whole (exit, signal)
    bool no_device = false;                       // no radeon ICD, or it opened no device
    bool ok() const { return error.empty(); }
};

// What:   compiles every source on each target's null device (never lavapipe: the caller
//         leaves it out), one worker per family at once (up to `workers`), each with a job
//         directory of its own under `scratch`; an alias shares its ISA's run. `worker` is the
//         watergen executable (a test names it: its own executable is the test's).
// Output: one run per target, in the order given. A pipeline the driver refuses has its
//         error; a worker that died leaves its target's run with the error and no pipelines.
// Cost:   2-20 ms per pipeline and family, plus ~50 ms per worker start.
std::vector<AcoTargetRun>
compile_on_targets(const std::vector<GpuTarget>& targets,
                   const std::vector<AcoPipelineSource>& sources,
                   const std::filesystem::path& scratch, unsigned workers,
                   const std::filesystem::path& worker = own_executable());

// The job directory the worker reads: `sources`' SPIR-V and reflection files and job.json; ""
// or why it could not be written.
std::string write_aco_job(const std::filesystem::path& dir,
                          const std::vector<AcoPipelineSource>& sources, bool disassembly);

// The worker: reads DIR/job.json, compiles each pipeline on the null device the environment
// names, writes DIR/result.json. Returns the exit code: 0, 3 without a device, 2 for a job it
// cannot read.
int run_aco_worker(const std::filesystem::path& dir);

} // namespace watergen
