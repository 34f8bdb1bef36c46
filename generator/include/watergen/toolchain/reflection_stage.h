// Reflection stage: the shader interface (descriptors, block layouts, stage I/O) read back
// from SPIR-V with SPIRV-Cross, in the runtime's Reflection form.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "watergen/ir/core/diagnostic.h"
#include "watergen/runtime/reflection.h"

namespace watergen {

struct ReflectResult {
    Reflection reflection;
    Diagnostics diagnostics;
};

// What:   reflects the descriptors and user inputs/outputs the entry point statically
//         uses (built-ins such as gl_Position are left out). Unused ones are skipped on
//         purpose: the HLSL path (glslang + legalisation) removes unread textures and
//         inputs, the GLSL path keeps them, and both paths must reflect the same interface.
//         Uniform/storage blocks are named by their block TYPE name ("WaterParams"), so
//         a GLSL `uniform WaterParams {...} params;` and an HLSL `cbuffer WaterParams`
//         reflect the same; blocks list all members with declared names and explicit
//         offsets. Types use GLSL spelling (float, vec3, mat4, int, uint, ...). Bindings
//         are sorted by (set, binding), inputs/outputs by location. Scalar
//         specialization constants are listed by constant id with name, type and default;
//         their range is left 0 (not in SPIR-V; add_specialization_ranges fills it).
// Inputs: a SPIR-V module (the toolchain reflects the unoptimised one, which still has
//         every name glslang emitted), the stage whose entry point to describe, and a
//         file name for diagnostics.
// Output: the reflection; Error diagnostics when the module has no entry point for the
//         stage or SPIRV-Cross cannot parse it; Warnings for descriptor kinds Reflection
//         cannot express (storage images, push constants, ...), which are skipped.
// Cost:   well under 1 ms for a 100-line shader. Thread-safe.
ReflectResult reflect_spirv(const std::vector<uint32_t>& spirv, ShaderStage stage,
                            const std::string& file_name = "");

} // namespace watergen
