#include "watergen/eval/measure/gpu_cost.h"

#include "watergen/eval/draw/mesh_render.h"

#include <thread>

namespace watergen {

namespace {

// RADV 22.3's names for the statistics (radv_shader.c, aco_statistics).
StageGpuCost stage_cost(const AcoStageStatistics& s) {
    StageGpuCost c;
    c.stage = s.stage;
    c.instructions = s.value("Instructions");
    c.vgprs = s.value("VGPRs");
    c.sgprs = s.value("SGPRs");
    c.spilled_vgprs = s.value("Spilled VGPRs");
    c.spilled_sgprs = s.value("Spilled SGPRs");
    c.scratch_bytes = s.value("Scratch size");
    c.code_bytes = s.value("Code size");
    c.waves_per_simd = s.value("Subgroups per SIMD");
    c.latency = s.value("Latency");
    c.inverse_throughput = s.value("Inverse Throughput");
    c.loops = static_cast<uint32_t>(s.loops.size());
    return c;
}

// The IR's loops the driver must keep: those written [[dont_unroll]], with their depth among
// themselves.
std::vector<EmittedLoop> kept_loops(const std::vector<EmittedLoop>& ir) {
    std::vector<EmittedLoop> kept;
    std::vector<uint32_t> open; // depths (in the IR) of the kept loops around the current one
    for (const EmittedLoop& l : ir) {
        while (!open.empty() && open.back() >= l.depth)
            open.pop_back();
        if (l.hint != UnrollHint::Keep) continue;
        EmittedLoop k = l;
        k.depth = static_cast<uint32_t>(open.size());
        kept.push_back(k);
        open.push_back(l.depth);
    }
    return kept;
}

bool same_nesting(const std::vector<AsmLoop>& loops, const std::vector<EmittedLoop>& ir) {
    if (loops.size() != ir.size()) return false;
    for (size_t i = 0; i < ir.size(); ++i)
        if (loops[i].depth != ir[i].depth) return false;
    return true;
}

// The driver's loops against the IR's, in program order: every IR loop, or (the driver having
// unrolled the rest, whose copies are in the static count already) those written
// [[dont_unroll]]; matched only where the counts and nesting depths agree. A driver that
// unrolled every loop leaves a static count that is already per pixel.
void estimate_per_pixel(const AcoStageStatistics& s, const std::vector<EmittedLoop>& ir,
                        StageGpuCost& c) {
    if (!s.has_disassembly) {
        c.per_pixel_note = "no disassembly of this family (Mesa disassembles gfx6 with CLRX, "
                           "which Debian does not package): the static count stands in";
        return;
    }
    if (s.loops.empty()) {
        c.per_pixel = c.instructions;
        c.per_pixel_note = ir.empty() ? "no loops" : "the driver unrolled every loop";
        return;
    }
    const std::vector<EmittedLoop> kept = kept_loops(ir);
    const std::vector<EmittedLoop>* match = same_nesting(s.loops, ir)     ? &ir
                                            : same_nesting(s.loops, kept) ? &kept
                                                                          : nullptr;
    if (!match) {
        c.per_pixel_note = "the driver kept " + std::to_string(s.loops.size()) + " of the " +
                           std::to_string(ir.size()) + " loops (" + std::to_string(kept.size()) +
                           " written [[dont_unroll]]): which is which is not known";
        return;
    }
    AsmListing listing;
    listing.loops = s.loops;
    std::vector<double> trips;
    for (const EmittedLoop& l : *match)
        trips.push_back(l.trip_count);
    // The static count is the driver's own figure; the weights add what the loops repeat.
    for (const AsmLoop& l : s.loops)
        listing.instructions = std::max(listing.instructions, l.last + 1);
    const auto weighted = weighted_instructions(listing, trips);
    c.per_pixel = c.instructions + (*weighted - listing.instructions);
    c.per_pixel_note = match == &ir ? "every loop weighted by its trip count"
                                    : "the kept loops weighted by their trip counts";
}

} // namespace

const StageGpuCost* PipelineGpuCost::stage(const std::string& name) const {
    for (const auto& s : stages)
        if (s.stage == name) return &s;
    return nullptr;
}

double PipelineGpuCost::fragment_cost() const {
    const StageGpuCost* f = stage("fragment");
    if (!f) return -1;
    return f->per_pixel ? *f->per_pixel : f->instructions;
}

AcoPipelineSource aco_source(const LanguageBuild& lang, const std::string& name,
                             const std::map<uint32_t, float>& specialization) {
    AcoPipelineSource s;
    s.name = name;
    s.vertex = lang.vertex.toolchain.spirv_optimized;
    s.fragment = lang.fragment.toolchain.spirv_optimized;
    s.vertex_reflection = lang.vertex.toolchain.reflection;
    s.fragment_reflection = lang.fragment.toolchain.reflection;
    s.specialization = specialization;
    if (draws_mesh(lang)) {
        // The grid's vertex input (grid_mesh: grid_xz, grid_lod), as quad patches when
        // tessellated.
        PipelineGeometry g;
        g.attribute_sizes = {2, 3};
        if (lang.tessellated()) {
            g.patch_control_points = 4;
            s.tess_control = lang.control.toolchain.spirv_optimized;
            s.tess_evaluation = lang.evaluation.toolchain.spirv_optimized;
            s.tess_control_reflection = lang.control.toolchain.reflection;
            s.tess_evaluation_reflection = lang.evaluation.toolchain.reflection;
        }
        s.geometry = g;
    }
    return s;
}

PipelineGpuCost gpu_cost(const AcoPipelineStatistics& stats,
                         const std::vector<EmittedLoop>& fragment_loops) {
    PipelineGpuCost out;
    out.name = stats.name;
    out.error = stats.error;
    out.unsupported = stats.unsupported;
    for (const auto& s : stats.stages) {
        StageGpuCost c = stage_cost(s);
        if (c.stage == "fragment")
            estimate_per_pixel(s, fragment_loops, c);
        else
            estimate_per_pixel(s, {}, c);
        out.stages.push_back(std::move(c));
    }
    return out;
}

const std::vector<GpuCostColumn>& gpu_cost_columns() {
    static const std::vector<GpuCostColumn> columns = {
        {"instructions", &StageGpuCost::instructions},
        {"vgprs", &StageGpuCost::vgprs},
        {"sgprs", &StageGpuCost::sgprs},
        {"spilled_vgprs", &StageGpuCost::spilled_vgprs},
        {"spilled_sgprs", &StageGpuCost::spilled_sgprs},
        {"scratch_bytes", &StageGpuCost::scratch_bytes},
        {"code_bytes", &StageGpuCost::code_bytes},
        {"waves_per_simd", &StageGpuCost::waves_per_simd},
        {"latency", &StageGpuCost::latency},
        {"inverse_throughput", &StageGpuCost::inverse_throughput},
    };
    return columns;
}

std::vector<TargetCosts> variant_gpu_costs(const std::vector<GpuTarget>& targets,
                                           const std::vector<const VariantBuild*>& builds,
                                           const std::vector<std::string>& names,
                                           const std::filesystem::path& scratch, LoopUnroll unroll,
                                           const std::filesystem::path& worker) {
    std::vector<AcoPipelineSource> sources;
    std::vector<std::vector<EmittedLoop>> loops;
    for (size_t i = 0; i < builds.size(); ++i) {
        const auto l = emitted_loops(builds[i]->shader.fragment, unroll);
        for (const LanguageBuild& lang : builds[i]->languages) {
            sources.push_back(
                aco_source(lang, names[i] + (lang.language == Language::Glsl ? " glsl" : " hlsl")));
            loops.push_back(l);
        }
    }
    const auto runs = compile_on_targets(targets, sources, scratch,
                                         std::max(1u, std::thread::hardware_concurrency()), worker);
    std::vector<TargetCosts> out;
    for (const auto& run : runs) {
        TargetCosts t;
        t.run = run;
        for (size_t i = 0; i < run.pipelines.size(); ++i)
            t.costs.push_back(gpu_cost(run.pipelines[i], loops[i]));
        out.push_back(std::move(t));
    }
    return out;
}

GlslFragmentCosts glsl_fragment_costs(const std::vector<GpuTarget>& targets,
                                      const std::vector<VariantBuild>& builds,
                                      const std::vector<std::string>& names, LoopUnroll unroll) {
    std::vector<const VariantBuild*> pointers;
    for (const VariantBuild& b : builds)
        pointers.push_back(&b);
    GlslFragmentCosts out;
    for (const TargetCosts& t : variant_gpu_costs(targets, pointers, names,
                                                  std::filesystem::temp_directory_path(), unroll)) {
        if (!t.run.ok()) {
            out.error = t.run.error;
            out.no_device = t.run.no_device;
            return out;
        }
        std::vector<std::optional<double>>& costs = out.costs.emplace_back();
        for (size_t i = 0; i < builds.size(); ++i) {
            const PipelineGpuCost& glsl = t.costs[2 * i];
            if (!glsl.ok() && !glsl.unsupported) {
                out.error = t.run.target.name + ": " + glsl.name + ": " + glsl.error;
                return out;
            }
            costs.push_back(glsl.unsupported ? std::nullopt
                                             : std::optional<double>(glsl.fragment_cost()));
        }
    }
    return out;
}

} // namespace watergen
