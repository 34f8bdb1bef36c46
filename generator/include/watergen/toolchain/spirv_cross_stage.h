// SPIRV-Cross stage: Vulkan SPIR-V back to GLSL 330 core, ESSL 300 and MSL.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "watergen/ir/core/diagnostic.h"

namespace watergen {

enum class CrossTarget { Glsl330, Essl300, Msl };

// The Metal index of the resource at a Vulkan (set, binding): its [[buffer(n)]], [[texture(n)]]
// or [[sampler(n)]], whichever its kind takes.
// The push-constant block has no set or binding: its slot says push_constant instead.
struct MslSlot {
    uint32_t set = 0, binding = 0, index = 0;
    bool push_constant = false;
};

struct CrossResult {
    std::string source; // empty when SPIRV-Cross failed
    Diagnostics diagnostics;
};

// What:   decompiles a SPIR-V module to one target language.
//         GLSL 330 / ESSL 300: separate textures and samplers are merged into combined
//         sampler2D uniforms named after the texture ("scene_color"; "<texture>_<sampler>"
//         only when one texture is used with several samplers); layout(binding) and set
//         qualifiers are dropped because neither 330 core nor ES 300 has them (the engine
//         binds by name); ES gets "precision highp float/int" defaults.
//         MSL: SPIRV-Cross default options (MSL 1.2, macOS), each resource of `msl` at its
//         index (the binding map's); the others where SPIRV-Cross counts them.
// Inputs: a valid SPIR-V module, the target, a file name for diagnostics
//         (the toolchain passes "<file>.330.glsl", "<file>.300es.glsl", "<file>.metal").
// Output: the source text, or diagnostics (SPIRV-Cross errors, prefixed "spirv-cross: ").
// Cost:   ~1 ms per target for a 100-line shader. Thread-safe (no shared state).
CrossResult cross_compile(const std::vector<uint32_t>& spirv, CrossTarget target,
                          const std::string& file_name, const std::vector<MslSlot>& msl = {});

// File-name suffix the toolchain uses for a target: ".330.glsl", ".300es.glsl", ".metal".
const char* cross_target_suffix(CrossTarget target);

} // namespace watergen
