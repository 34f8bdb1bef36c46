// The whole in-process toolchain for one generated shader.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "watergen/ir/core/diagnostic.h"
#include "watergen/runtime/reflection.h"
#include "watergen/toolchain/glslang_stage.h"

namespace watergen {

struct ToolchainOutputs {
    std::vector<uint32_t> spirv;           // validated, as compiled (HLSL: legalised)
    std::vector<uint32_t> spirv_optimized; // spirv-opt -O, validated again
    size_t instruction_count = 0;
    size_t instruction_count_optimized = 0;
    std::string glsl330, essl300, msl; // SPIRV-Cross output of the optimised module
    Reflection reflection;             // of the unoptimised module
    Diagnostics diagnostics;           // all stages; see run_toolchain for file names
    bool cross_compiled = false;       // SPIRV-Cross ran (CrossCompile::No: it did not)
    bool ok() const { return !spirv.empty() && !has_errors(diagnostics); }
};

// What:   compile -> spirv-val -> spirv-opt -> spirv-val -> SPIRV-Cross (GLSL 330, ESSL 300,
//         MSL, from the optimised module) -> round trip (check_glsl on the 330 and ES 300
//         text) -> reflection of the unoptimised module. Stops after the first stage that
//         reports an error (the three SPIRV-Cross targets all run before stopping), and
//         leaves later outputs empty. Compute shaders skip the GLSL 330 / ESSL 300 outputs
//         and their round trip (neither language has compute) with a Note; tessellation
//         stages skip all three (neither GL language has them, and Metal tessellation is a
//         compute kernel SPIRV-Cross writes only under its own pipeline options), with a Note.
//         Diagnostic::file says which stage spoke, with F = request.file_name:
//           F               glslang (lines are lines of request.source)
//           F.spv           spirv-val of the compiled module, reflection
//           F.opt.spv       spirv-opt and spirv-val of the optimised module
//           F.330.glsl      SPIRV-Cross to GLSL 330 and its round trip (lines of glsl330)
//           F.300es.glsl    same for ESSL 300 (lines of essl300)
//           F.metal         SPIRV-Cross to MSL
// Inputs: the compile request. Calls glslang_warm_up() itself.
// Output: everything above; ok() when no stage reported an error.
// Cost:   ~12 ms for a 100-line fragment shader after warm-up (spirv-opt ~40% of it),
//         against ~100-160 ms through the CLI tools (run_tool_process_chain). Thread-safe,
//         so many shaders can go through in parallel.
//         With CrossCompile::No the chain skips SPIRV-Cross and the round trip (their outputs
//         stay empty): for a module whose cross-compiled text nobody ships.
enum class CrossCompile { Yes, No };
ToolchainOutputs run_toolchain(const CompileRequest& request,
                               CrossCompile cross = CrossCompile::Yes);

} // namespace watergen
