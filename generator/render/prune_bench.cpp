#include "watergen/render/prune_bench.h"

#include <algorithm>
#include <set>

#include "watergen/ir/emitter.h"
#include "watergen/ir/ir_fold.h"
#include "watergen/pipeline/compile_bench.h"

namespace watergen {

namespace {

// The choices of the axes the material varies, without axis names (the CSV has keys).
std::string short_key(const Material& m, const Variant& v) {
    std::string key;
    for (size_t a = 0; a < axes().size(); ++a)
        if (m.space.choices[a].size() > 1) key += (key.empty() ? "" : ",") + v.choices[a];
    return key;
}

void summarise(PruneBenchScene& s) {
    std::vector<double> ir, spirv, opt, gpu, gpu_hlsl;
    for (const auto& row : s.rows) {
        const PruneMeasurement& r = row.measurement;
        ir.push_back(double(r.live_after) / r.live_before);
        spirv.push_back(double(r.spirv_pruned) / r.spirv_unpruned);
        opt.push_back(double(r.spirv_opt_pruned) / r.spirv_opt_unpruned);
        gpu.push_back(r.gpu_ms_pruned / r.gpu_ms_unpruned);
        gpu_hlsl.push_back(r.gpu_ms_pruned_hlsl / r.gpu_ms_unpruned_hlsl);
        s.worst = std::max(s.worst, row.max_diff);
    }
    s.ir = median(ir);
    s.spirv = median(spirv);
    s.spirv_opt = median(opt);
    s.gpu_glsl = median(gpu);
    s.gpu_hlsl = median(gpu_hlsl);
}

} // namespace

bool PruneBenchResult::within(double tolerance) const {
    for (const auto& s : scenes)
        for (const auto& row : s.rows)
            if (!(row.max_diff <= tolerance)) return false;
    return true;
}

PruneBenchResult bench_prune(VulkanRunner& runner, const Material& m,
                             const std::vector<ScenePlan>& plans, const PruneBenchOptions& o) {
    PruneBenchResult out;
    const SyntheticScene base = make_synthetic_scene(o.size, o.size);
    const RenderSettings settings{o.size, o.size, o.draws, false};
    for (const ScenePlan& sp : plans) {
        PruneBenchScene& s = out.scenes.emplace_back();
        s.name = sp.scene.name;
        const SyntheticScene scene = conform_scene(base, sp, m, &s.notes);
        // One measurement per distinct folded shader.
        std::set<std::string> shapes;
        for (const Variant& v : sp.variants) {
            if (o.per_scene && shapes.size() >= o.per_scene) break;
            const WaterShader shader = m.compose(v);
            if (has_errors(shader.fragment.diagnostics())) continue;
            Diagnostics ignored;
            const FoldResult folded = fold_graph(shader.fragment, sp.facts);
            if (!shapes.insert(emit_fragment(folded.graph, Language::Glsl, "f", "", ignored).source)
                     .second)
                continue;
            PruneMeasurement r = measure_pruning(runner, m, sp, v, scene, settings, o.rounds);
            if (!r.ok()) {
                out.error = sp.scene.name + ": " + v.key() + ": " + r.error;
                return out;
            }
            const double diff = std::max({r.max_abs_glsl, r.max_abs_hlsl, r.max_abs_cpu});
            s.rows.push_back({v.key(), short_key(m, v), std::move(r), diff});
        }
        summarise(s);
        s.complete = true;
    }
    return out;
}

} // namespace watergen
