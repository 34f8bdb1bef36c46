// The tessellated mesh path through emitters and toolchain: four stages per language (patch
// vertex, tessellation control, tessellation evaluation, fragment), each validated by spirv-val,
// optimised and reflected. The patch stages declare one shared parameter block, so the pipeline
// binds one uniform buffer. No cross-compilation target takes the patch stages (the toolchain
// skips them with a note); the vertex and fragment stages cross-compile as the mesh path's do.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "watergen/pipeline/variant_build.h"
#include "watergen/water/tessellated_mesh.h"

namespace watergen {

struct TessellatedLanguageBuild {
    Language language = Language::Glsl;
    StageBuild vertex, control, evaluation, fragment;
};

struct TessellatedMeshBuild {
    TessellatedMeshShader shader;
    // The block both patch stages declare (shared_block_parameters of control and evaluation);
    // pack a job's uniforms with either patch stage's interface.
    std::vector<Parameter> block;
    std::array<TessellatedLanguageBuild, 2> languages; // GLSL, HLSL
    Diagnostics diagnostics;
    bool ok() const { return !has_errors(diagnostics); }
};

// Emits build_tessellated_mesh_shader(wave_model) in both languages (files
// <lang>/mesh_tess_<model>.<vert|tesc|tese|frag>.<glsl|hlsl>; skeletons mesh_patch.vert, mesh.tesc,
// mesh.tese and the fragment skeleton) with the default binding map, and runs every stage
// through the toolchain. Stops at the first language with emission errors. A few tens of ms.
TessellatedMeshBuild build_tessellated_mesh(const std::string& wave_model);

} // namespace watergen
