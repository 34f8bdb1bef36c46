#include "watergen/plan/shader_fold.h"

#include <algorithm>

namespace watergen {

namespace {

bool declares(const Graph& g, const std::string& name) {
    if (g.find_parameter(name)) return true;
    return std::any_of(g.textures().begin(), g.textures().end(),
                       [&](const TextureInput& t) { return t.name == name; });
}

} // namespace

FoldReport fold_water_shader(WaterShader& shader, const FoldFacts& facts) {
    FoldResult fragment = fold_graph(shader.fragment, facts);
    shader.fragment = std::move(fragment.graph);
    FoldReport report = std::move(fragment.report);
    if (!shader.mesh) return report;
    std::vector<RemovedInput> removed_parameters, removed_textures;
    for (Graph* stage : shader.mesh->graphs()) {
        FoldResult r = fold_graph(*stage, facts);
        *stage = std::move(r.graph);
        removed_parameters.insert(removed_parameters.end(), r.report.removed_parameters.begin(),
                                  r.report.removed_parameters.end());
        removed_textures.insert(removed_textures.end(), r.report.removed_textures.begin(),
                                r.report.removed_textures.end());
        for (const auto& [name, value] : r.report.folded_parameters)
            report.folded_parameters.emplace(name, value);
    }
    // Removed from the shader when no stage still reads it; once each.
    auto still_read = [&](const std::string& name) {
        if (declares(shader.fragment, name)) return true;
        for (const Graph* stage : std::as_const(shader.mesh)->graphs())
            if (declares(*stage, name)) return true;
        return false;
    };
    auto merge = [&](std::vector<RemovedInput>& into, const std::vector<RemovedInput>& more) {
        std::vector<RemovedInput> kept;
        for (const RemovedInput& r : into)
            if (!still_read(r.name)) kept.push_back(r);
        for (const RemovedInput& r : more)
            if (!still_read(r.name) &&
                std::none_of(kept.begin(), kept.end(),
                             [&](const RemovedInput& k) { return k.name == r.name; }))
                kept.push_back(r);
        into = std::move(kept);
    };
    merge(report.removed_parameters, removed_parameters);
    merge(report.removed_textures, removed_textures);
    return report;
}

} // namespace watergen
