// Emitter machinery shared with the emitters of other stages (vertex_emitter.cpp). Not public.
#pragma once

#include <string_view>

#include "watergen/ir/emitter.h"

namespace watergen {

// Fills `skeleton` (template text) from `g` exactly as the fragment emitter does: blocks
// stamp, declarations (uniforms, textures, and each live Varying as `in` at location = its
// index), prelude, inputs (HLSL entry parameters), body, and one block output_<name> per output
// of `g` holding its expression.
EmittedShader emit_from_skeleton(const Graph& g, Language language, ShaderStage stage,
                                 std::string_view skeleton, const std::string& file_name,
                                 const std::string& variant_key, Diagnostics& diagnostics,
                                 const BindingMap* bindings = nullptr);

} // namespace watergen
