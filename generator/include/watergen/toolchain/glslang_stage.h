// Front end of the toolchain: glslang turns generated GLSL 450 / HLSL into SPIR-V, and
// re-parses SPIRV-Cross output to prove it still compiles.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "watergen/ir/core/diagnostic.h"
#include "watergen/runtime/reflection.h"
#include "watergen/toolchain/spirv_cross_stage.h"

namespace watergen {

enum class SourceLanguage { Glsl, Hlsl };

struct CompileRequest {
    SourceLanguage language = SourceLanguage::Glsl;
    ShaderStage stage = ShaderStage::Fragment;
    std::string source;
    std::string file_name;            // used as Diagnostic::file
    std::string entry_point = "main"; // HLSL function to compile; GLSL always uses main()
    // HLSL only (dxc's -enable-16bit-types): `half` and `min16float` become binary16
    // (OpTypeFloat 16, capability Float16) instead of 32-bit floats (min16float marked
    // RelaxedPrecision). glslang 12 does not know `float16_t` in HLSL either way. GLSL asks
    // for 16-bit types itself, with GL_EXT_shader_explicit_arithmetic_types_float16.
    bool hlsl_16bit_types = false;
    // The Metal index ([[buffer]], [[texture]] or [[sampler]] by the resource's kind) of each
    // Vulkan (set, binding), from the binding map; a slot not listed keeps SPIRV-Cross's own.
    std::vector<MslSlot> msl_bindings = {};
};

struct SpirvResult {
    std::vector<uint32_t> spirv; // empty when compilation failed
    Diagnostics diagnostics;
    bool ok() const { return !spirv.empty() && !has_errors(diagnostics); }
};

// What:   initialises glslang for the process (exactly once, std::call_once) and compiles
//         one tiny shader so the first real compile does not pay for built-in symbol tables.
// Inputs: none. Safe to call from any thread, any number of times.
// Output: none; glslang is never finalised (it lives until process exit).
// Cost:   first call ~75 ms (GLSL 450 built-in tables), later calls a once-flag check.
//         Other versions/languages (HLSL, 330, 300 es) build their tables on first use.
void glslang_warm_up();

// What:   compiles one shader to SPIR-V 1.3 for Vulkan 1.1. GLSL must be `#version 450`;
//         HLSL goes through glslang's HLSL front end with `entry_point`, and the result is
//         legalised with the SPIRV-Tools legalisation recipe (HLSL-to-SPIR-V output is not
//         valid Vulkan SPIR-V until then). HLSL varyings (vertex and domain outputs,
//         fragment inputs) flattened from structs lose glslang's "@entryPointOutput." /
//         "param." prefix, so
//         GLSL 330 / ESSL 300 output (which links varyings by name) of an HLSL vertex and
//         fragment pair still links. glslang info-log lines become Diagnostics with
//         file = request.file_name and the line glslang reported.
// Inputs: a request; calls glslang_warm_up() itself.
// Output: SPIR-V words plus diagnostics (warnings may accompany a success).
// Cost:   ~1 ms (GLSL) / ~5 ms (HLSL, mostly legalisation) for a 100-line shader.
//         Thread-safe: independent compiles may run concurrently.
SpirvResult compile_to_spirv(const CompileRequest& request);

enum class GlslProfile { Core330, Es300 };

// What:   parses and links GLSL for OpenGL (no SPIR-V), as the round-trip check of
//         SPIRV-Cross output. Also reports an error when the `#version` line is not the
//         one `profile` asks for (330 / 300 es).
// Inputs: GLSL source text, its stage, the expected profile, a file name for diagnostics.
// Output: diagnostics; empty (or warnings only) means the source is valid.
// Cost:   ~1 ms for a 100-line shader. Thread-safe.
Diagnostics check_glsl(const std::string& source, ShaderStage stage, GlslProfile profile,
                       const std::string& file_name);

// What:   turns a glslang info log into diagnostics ("ERROR: 0:12: msg" -> Error, line 12,
//         message "msg"). Lines without a location get line 0; the trailing
//         "N compilation errors." summary is dropped, continuation lines are appended.
// Inputs: the log text and the file name to put into each diagnostic.
// Output: diagnostics in log order. Cost: linear in the log size.
Diagnostics parse_glslang_log(const std::string& log, const std::string& file_name);

} // namespace watergen
