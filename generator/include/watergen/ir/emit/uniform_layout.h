// Places the parameters a shader reads into one uniform block with explicit offsets that are
// valid under both std140 (GLSL) and HLSL cbuffer packing, so both languages' SPIR-V share one
// layout and one byte buffer feeds either.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "watergen/ir/core/ir.h"
#include "watergen/ir/core/shader_values.h"

namespace watergen {

struct UniformSlot {
    std::string name;
    Type type = Type::Float;
    uint32_t offset = 0;     // bytes
    uint32_t array_size = 0; // 0: not an array; else elements, each kArrayStride bytes apart
};

// std140 and HLSL cbuffers both start each array element on a 16-byte register.
constexpr uint32_t kArrayStride = 16;

struct UniformLayout {
    std::vector<UniformSlot> members; // ascending offset
    uint32_t size = 0;                // bytes, a multiple of 16
};

// Parameters in declaration order; larger members are placed first, each at the lowest offset
// aligned to its size class (vec3/vec4: 16, vec2: 8, float: 4) that does not straddle a
// 16-byte register. An array (Parameter::array_size) goes first, at a register boundary, one
// register per element (std140's stride for float..vec4 elements, and packoffset's), and
// nothing shares its registers. Deterministic for a given input. Parameters marked
// `specialization` are skipped: they are specialization constants, not block members.
UniformLayout layout_uniforms(const std::vector<Parameter>& parameters, Diagnostics& diagnostics);

// Writes parameter values (double -> float) at their offsets, array elements kArrayStride
// apart: the value in `overrides` when present (and of the right size, every element of an
// array), else the parameter's default, through its host rule (shader_values.h) in the frame
// of `centre` (by default the eye's).
std::vector<uint8_t> pack_uniforms(const UniformLayout& layout,
                                   const std::vector<Parameter>& parameters,
                                   const std::map<std::string, std::vector<double>>& overrides = {},
                                   const std::optional<FrameCentre>& centre = std::nullopt);

} // namespace watergen
