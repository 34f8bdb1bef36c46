// Vertex stages written with the DSL (the mesh path: wave displacement on a grid).
#pragma once

#include <string>

#include "watergen/ir/emit/emitter.h"

namespace watergen {

// Emits the vertex stage of `g` into the skeleton templates/<language>/<skeleton>.vert.<ext>
// (e.g. skeleton "mesh" -> glsl/mesh.vert.glsl, hlsl/mesh.vert.hlsl). Each live Varying of `g`
// is a vertex attribute (location = its index in creation order); the output "position"
// (vec4, clip space) is required, and every other output must be one the skeleton writes.
// `block`: the parameter block the pipeline's stages share (EmitOptions::block); null: the
// parameters `g` reads.
EmittedShader emit_vertex(const Graph& g, Language language, const std::string& skeleton,
                          const std::string& file_name, const std::string& variant_key,
                          Diagnostics& diagnostics, const BindingMap* bindings = nullptr,
                          const std::vector<Parameter>* block = nullptr);

} // namespace watergen
