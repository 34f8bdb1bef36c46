// The toolchain run through the command-line tools as child processes. Exists only so a
// benchmark can compare it with the in-process run_toolchain(); nothing else uses it.
#pragma once

#include <string>

#include "watergen/toolchain/glslang_stage.h"

namespace watergen {

struct ProcessChainResult {
    bool ok = false;
    std::string error; // "<tool>: exit status N\n<its stderr (or stdout)>" when !ok
};

// What:   the same steps as run_toolchain, one child process each (posix_spawnp, no shell,
//         each awaited before the next):
//           glslangValidator -V --target-env vulkan1.1 -S <stage> [-D -e <entry>] -o shader.spv
//           spirv-val --target-env vulkan1.1 shader.spv
//           spirv-opt -O --skip-validation shader.spv -o shader.opt.spv (in-process skips it too)
//           spirv-val --target-env vulkan1.1 shader.opt.spv
//           spirv-cross shader.opt.spv --version 330 --no-es --no-420pack-extension
//           spirv-cross shader.opt.spv --es --version 300
//           spirv-cross shader.opt.spv --msl
//           glslangValidator -S <stage> on the 330 and the 300 es output (the round trip)
//           spirv-cross shader.spv --reflect
// Inputs: the request and a directory for the intermediate files (created if missing;
//         files are named shader.*, so use one directory per concurrent call).
// Output: ok, or the first failing tool's name, exit status and stderr (stdout when stderr
//         is empty: glslangValidator reports errors on stdout).
// Cost:   ~100-160 ms for a 100-line shader, mostly glslangValidator rebuilding its
//         built-in symbol tables in every process (~80 ms for GLSL 450).
ProcessChainResult run_tool_process_chain(const CompileRequest& request,
                                          const std::string& work_dir);

} // namespace watergen
