#include "watergen/eval/compare/compare_caustics.h"

#include <algorithm>

#include "watergen/water/nodes/caustics.h"

namespace watergen {

struct CompareCaustics::Pass {
    CausticsPassBuild build;
    uint32_t texels = 0;
    std::map<size_t, SceneCausticsPass> views; // drawn so far, by view
};

CompareCaustics::CompareCaustics(VulkanRunner& runner,
                                 const std::vector<std::pair<std::string, SyntheticScene>>& views,
                                 Material material)
    : runner_(runner), views_(views), material_(std::move(material)) {}

CompareCaustics::~CompareCaustics() = default;

std::map<std::string, TextureData> CompareCaustics::textures_for(const VariantBuild& water,
                                                                 size_t view, std::string* error) {
    const Variant& variant = water.shader.variant;
    const auto method = caustics_pass_method(variant.choice("caustics"));
    if (!method || view >= views_.size()) return {};
    const SyntheticScene& scene = views_[view].second;
    const uint32_t texels = scene_caustics_texels(water, scene);
    const std::string waves = variant.choice("waves");
    auto it = std::find_if(passes_.begin(), passes_.end(), [&](const auto& p) {
        return p->build.pass.method == *method && p->build.pass.wave_model == waves &&
               p->texels == texels;
    });
    if (it == passes_.end()) {
        passes_.push_back(std::make_unique<Pass>(
            Pass{build_caustics_pass_files(material_, {*method, waves}), texels, {}}));
        it = std::prev(passes_.end());
    }
    Pass& pass = **it;
    auto drawn = pass.views.find(view);
    if (drawn == pass.views.end())
        drawn = pass.views
                    .emplace(view, draw_scene_caustics_pass(runner_, pass.build, scene, texels, 0))
                    .first;
    if (!drawn->second.ok()) {
        *error = drawn->second.error;
        return {};
    }
    return {{caustics_map_texture().name, caustics_texture(drawn->second.intensity, texels)}};
}

std::vector<ComparedCausticsPass> CompareCaustics::time(uint32_t rounds, uint32_t draws,
                                                        RatioInterval* aa, std::string* error) {
    std::vector<ComparedCausticsPass> out;
    std::vector<RenderJob> jobs;
    for (const auto& pass : passes_) {
        // Each pass is drawn for every view before timing: the first view is there.
        auto first = pass->views.find(0);
        if (first == pass->views.end()) continue;
        ComparedCausticsPass c;
        c.name = std::string(to_string(pass->build.pass.method)) + ", " +
                 pass->build.pass.wave_model + " waves";
        c.first = first->second;
        const auto values = scene_caustics_values(pass->build, views_[0].second);
        jobs.push_back(caustics_job(pass->build, 0, values,
                                    scene_caustics_settings(c.first.method, pass->texels, 0),
                                    error));
        if (!error->empty()) return {};
        out.push_back(std::move(c));
    }
    if (jobs.empty()) return out;
    const InterleavedTiming t = time_interleaved(runner_, jobs, rounds, draws);
    if (!t.ok()) {
        *error = "caustics pass timing: " + t.error;
        return {};
    }
    *aa = t.aa;
    for (size_t i = 0; i < out.size(); ++i) {
        ComparedCausticsPass& c = out[i];
        c.round_ms = round_medians(t.results[i].draw_ms, draws);
        std::vector<double> sorted = c.round_ms;
        std::sort(sorted.begin(), sorted.end());
        if (!sorted.empty()) {
            const size_t n = sorted.size();
            c.median_ms = (sorted[(n - 1) / 2] + sorted[n / 2]) / 2;
            c.min_ms = sorted.front();
            c.max_ms = sorted.back();
        }
        c.vs_first_pass = t.ratios[i];
    }
    return out;
}

std::vector<CausticsPassFigures>
caustics_pass_figures(const std::vector<ComparedCausticsPass>& passes) {
    std::vector<CausticsPassFigures> out;
    for (const ComparedCausticsPass& c : passes) {
        const SceneCausticsPass& p = c.first;
        out.push_back({.name = c.name,
                       .texels = p.texels,
                       .pass = p.intensity,
                       .reference = p.reference,
                       .max_abs = p.vs_reference.max_abs,
                       .rmse = p.vs_reference.rmse,
                       .mean_difference = p.vs_reference.mean_difference,
                       .mean = p.mean,
                       .reference_mean = p.reference_mean,
                       .glsl_vs_hlsl = p.glsl_vs_hlsl,
                       .median_ms = c.median_ms,
                       .min_ms = c.min_ms,
                       .max_ms = c.max_ms,
                       .rounds = uint32_t(c.round_ms.size()),
                       .ratio = c.vs_first_pass.ratio,
                       .ratio_lo = c.vs_first_pass.lo,
                       .ratio_hi = c.vs_first_pass.hi});
    }
    return out;
}

} // namespace watergen
