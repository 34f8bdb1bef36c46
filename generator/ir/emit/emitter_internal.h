// Emitter machinery shared with the emitters of other stages (vertex_emitter.cpp,
// tessellation_emitter.cpp). Not public.
#pragma once

#include <string_view>

#include "watergen/ir/emit/emitter.h"

namespace watergen {

// Fills `skeleton` (template text) from `g` exactly as the fragment emitter does: blocks
// stamp, declarations (uniforms, textures, and each live Varying as `in` at location = its
// index), prelude, inputs (HLSL entry parameters), body, and one block output_<name> per output
// of `g` holding its expression.
EmittedShader emit_from_skeleton(const Graph& g, Language language, ShaderStage stage,
                                 std::string_view skeleton, const std::string& file_name,
                                 const std::string& variant_key, Diagnostics& diagnostics,
                                 const BindingMap* bindings = nullptr);

struct SkeletonOptions {
    const BindingMap* bindings = nullptr;
    // The skeleton defines every Varying of the graph as a local before {{body}} (the patch
    // stages: corners read from the input patch, the grid point interpolated over it), so none
    // is declared as a stage input or an HLSL entry parameter.
    bool skeleton_defines_varyings = false;
    // The parameter block's members when the stages of one pipeline share it (they bind one
    // uniform buffer, so each must declare the same layout); null: the parameters `g` reads.
    // A parameter `g` reads that the block lacks is an error.
    const std::vector<Parameter>* block = nullptr;
};
EmittedShader emit_from_skeleton(const Graph& g, Language language, ShaderStage stage,
                                 std::string_view skeleton, const std::string& file_name,
                                 const std::string& variant_key, Diagnostics& diagnostics,
                                 const SkeletonOptions& options);

// The parameters the live nodes of `g` (loop bodies and switch cases included) read, in
// declaration order.
std::vector<Parameter> parameters_read(const Graph& g);

} // namespace watergen
