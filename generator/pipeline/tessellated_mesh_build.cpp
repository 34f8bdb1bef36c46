#include "watergen/pipeline/tessellated_mesh_build.h"

#include "watergen/ir/tessellation_emitter.h"
#include "watergen/ir/vertex_emitter.h"

namespace watergen {

namespace {

std::string file_name(Language lang, ShaderStage stage, const std::string& stem) {
    return std::string(to_string(lang)) + "/" + stem + "." + file_extension(lang, stage);
}

} // namespace

TessellatedMeshBuild build_tessellated_mesh(const std::string& wave_model) {
    TessellatedMeshBuild b{build_tessellated_mesh_shader(wave_model), {}, {}, {}};
    const TessellatedMeshShader& s = b.shader;
    for (const Graph* g : {&s.patch_vertex, &s.control, &s.evaluation, &s.fragment})
        b.diagnostics.insert(b.diagnostics.end(), g->diagnostics().begin(), g->diagnostics().end());
    if (!b.ok()) return b;
    b.block = shared_block_parameters({&s.evaluation, &s.control}, b.diagnostics);
    const BindingMap map = default_map_for({&s.control, &s.evaluation, &s.fragment});
    const std::string stem = "mesh_tess_" + wave_model;
    const std::string key = "mesh_tess." + wave_model;
    const PatchStageOptions patch{&map, &b.block};
    constexpr Language kLanguages[] = {Language::Glsl, Language::Hlsl};
    for (size_t i = 0; i < b.languages.size() && b.ok(); ++i) {
        const Language lang = kLanguages[i];
        TessellatedLanguageBuild& out = b.languages[i];
        out.language = lang;
        Diagnostics& ds = b.diagnostics;
        out.vertex.source = emit_vertex(s.patch_vertex, lang, "mesh_patch",
                                        file_name(lang, ShaderStage::Vertex, stem), key, ds, &map);
        out.control.source =
            emit_tess_control(s.control, lang, "mesh",
                              file_name(lang, ShaderStage::TessControl, stem), key, ds, patch);
        out.evaluation.source = emit_tess_evaluation(
            s.evaluation, lang, "mesh", file_name(lang, ShaderStage::TessEvaluation, stem), key, ds,
            patch);
        out.fragment.source =
            emit_fragment(s.fragment, lang, file_name(lang, ShaderStage::Fragment, stem), key, ds,
                          EmitOptions{false, {}, LoopUnroll::AsHinted, &map});
        if (!b.ok()) break;
        for (StageBuild* stage : {&out.vertex, &out.control, &out.evaluation, &out.fragment})
            *stage = build_stage(std::move(stage->source), ds);
    }
    return b;
}

} // namespace watergen
