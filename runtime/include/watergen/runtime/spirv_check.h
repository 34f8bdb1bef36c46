// Checks a SPIR-V module before it reaches a Vulkan driver. Drivers trust the module they are
// given: a fragment slot holding a vertex module crashed lavapipe, and a truncated or
// byte-flipped module made it allocate gigabytes. ShaderBuild::spirv() runs both checks on every
// file it hands out; VariantPipeline::create() runs check_spirv() on the modules it is given.
// Part of watergen::runtime.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "watergen/runtime/reflection.h"

namespace watergen {

// The largest module the runtime accepts. The generator's largest shader (the full material's
// fragment stage with every node) is a few tens of KB of optimised SPIR-V; 4 MiB leaves two
// orders of magnitude for materials to grow and keeps a module far from what a driver chokes on.
constexpr size_t kMaxSpirvBytes = size_t(4) << 20;

// The module's words, structurally: size (a whole number of words, at least the 5-word header,
// at most kMaxSpirvBytes), magic number in this machine's byte order, a SPIR-V 1.0-1.6 version,
// an id bound of at most 4,194,303 (the SPIR-V limit), every instruction's word count inside
// the module, and an OpEntryPoint of the stage's execution model (Vertex, Fragment, GLCompute)
// named `entry_point` (any name when `entry_point` is empty). Linear in the module's size.
// False and `why` ("has no OpEntryPoint Fragment (its entry points: Vertex main); expected the
// fragment stage's module") otherwise.
bool check_spirv(std::span<const uint32_t> words, ShaderStage stage, const std::string& entry_point,
                 std::string* why);

// spirv-val (SPIRV-Tools' validator, Vulkan 1.1 rules as the generator validates with): false
// and `why` (the validator's first message) for a module it rejects. Costs a few times what
// check_spirv() does (docs/engine-guide.md gives the measured figure).
bool validate_spirv(std::span<const uint32_t> words, std::string* why);

} // namespace watergen
