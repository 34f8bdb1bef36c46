// SPIRV-Tools stages: validation, optimisation, legalisation, counting and disassembly.
// All run in-process against the Vulkan 1.1 environment (SPIR-V 1.3).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "watergen/ir/core/diagnostic.h"

namespace watergen {

// What:   spirv-val for Vulkan 1.1 (default validator options, like the CLI; the friendly
//         names only for a module with messages, which is validated twice).
// Inputs: a SPIR-V module; file_name goes into each diagnostic.
// Output: one Error diagnostic per validator message, message prefixed "spirv-val: ", ids
//         named as the CLI names them (%name from OpName); empty means valid. Line is 0
//         (SPIR-V has no source lines).
// Cost:   ~1 ms for a 100-line shader. Thread-safe.
Diagnostics validate_spirv(const std::vector<uint32_t>& spirv, const std::string& file_name);

struct OptimizeResult {
    std::vector<uint32_t> spirv; // empty when the optimiser failed
    Diagnostics diagnostics;
};

// What:   spirv-opt -O (Optimizer::RegisterPerformancePasses) for Vulkan 1.1. The
//         optimiser's own pre-validation is skipped: the toolchain always validates first,
//         and running it twice doubled the cost. Do not feed it unvalidated modules.
// Inputs: a valid SPIR-V module; file_name for diagnostics.
// Output: the optimised module plus optimiser messages (prefixed "spirv-opt: ").
// Cost:   ~3-5 ms for a 100-line shader (the largest in-process stage). Thread-safe.
OptimizeResult optimize_spirv(const std::vector<uint32_t>& spirv, const std::string& file_name);

// What:   the SPIRV-Tools legalisation recipe (Optimizer::RegisterLegalizationPasses),
//         which HLSL front ends need: it inlines, scalar-replaces and forwards opaque
//         handles (Texture2D / SamplerState copies) so the module becomes valid Vulkan.
// Inputs: glslang's raw HLSL-path output (not yet valid, so no validation beforehand).
// Output: the legal module plus messages (prefixed "spirv-opt: ").
// Cost:   ~3 ms for a 100-line shader. Thread-safe.
OptimizeResult legalize_spirv(const std::vector<uint32_t>& spirv, const std::string& file_name);

// What:   offline specialization: the float specialization constants of `values`
//         (constant_id -> value; the others keep their defaults) set and frozen into plain
//         constants (SPIRV-Tools' set-spec-const-default-value, freeze-spec-const and
//         fold-spec-const-op-composite passes), then spirv-opt -O, which folds what the
//         constants decide and drops the branches they rule out; validated.
// Inputs: a valid SPIR-V module; file_name for diagnostics.
// Output: the frozen module (no specialization constants left), or empty with diagnostics.
// Cost:   one spirv-opt -O run (tens of ms for a water shader). Thread-safe.
OptimizeResult freeze_specialization(const std::vector<uint32_t>& spirv,
                                     const std::map<uint32_t, float>& values,
                                     const std::string& file_name);

// What:   number of instructions in the module, header excluded.
// Inputs: a SPIR-V module. Output: the count; a malformed tail is not counted.
// Cost:   one pass over the words.
size_t count_instructions(const std::vector<uint32_t>& spirv);

// What:   whether the module declares OpCapability `capability` (e.g. kCapabilityFloat16:
//         it computes in binary16, as a strict-half shader does).
// Inputs: a SPIR-V module. Output: true when declared; a malformed module stops the walk.
// Cost:   one pass over the capability section at the head of the module.
constexpr uint32_t kCapabilityFloat16 = 9;
bool declares_capability(const std::vector<uint32_t>& spirv, uint32_t capability);

// What:   spirv-dis text with friendly names and indentation.
// Inputs: a SPIR-V module. Output: the text, or "" if the module cannot be disassembled.
// Cost:   ~1 ms per 1000 instructions.
std::string disassemble_spirv(const std::vector<uint32_t>& spirv);

} // namespace watergen
