// `watergen compare`: variants rendered side by side over named views of the synthetic scene,
// each measured against one reference: image error per view, draw time against the reference
// (interleaved_timing.h), SPIR-V size, and how the variant relates to the reference (an
// approximation of it, or a different model, whose error is not an approximation error).
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "watergen/eval/image/image_metrics.h"
#include "watergen/eval/measure/interleaved_timing.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/runner/vulkan_runner.h"
#include "watergen/runtime/water_grid.h"
#include "watergen/water/presets.h"
#include "watergen/water/variant.h"

namespace watergen {

struct CompareRun;

struct CompareRequest {
    std::vector<Variant> variants; // in report order; duplicates are dropped
    // A variant rendered on the GPU, or nullopt: reference_for(variants) evaluated on the CPU
    // in double precision (the gold of every axis that varies).
    std::optional<Variant> reference;
    const Preset* preset = nullptr;
    std::vector<std::pair<std::string, SyntheticScene>> views; // name, scene (all one size)
    uint32_t rounds = 40, draws = 3;                           // timing, in the first view
    // How a variant is built; empty: build_variant(v, preset). A material's variants are
    // composed by the material (and, for a scene, folded under its facts: pick.h
    // build_for_scene); the CPU reference evaluates the reference's built fragment graph.
    std::function<VariantBuild(const Variant&)> build;
    // The fragment a CPU reference evaluates when the reference is a mesh variant (geometry
    // mesh or tessellated): its exact surface as `build` composes it (exact_surface_fragment
    // in mesh_render.h). Empty: composed with `preset` alone.
    std::function<Graph(const Variant&)> exact_surface;
    WaterGridDesc grid{};   // the grid a mesh variant is drawn over (RenderSettings::grid)
    bool both_paths = true; // false: the GLSL path only (the HLSL image is tested equal elsewhere)
    // Textures that replace a view's (by binding name) for one built variant, e.g. the caustics
    // map its own pass drew (compare_caustics.h); empty: the view's scene as it is. Used for
    // the images, the CPU reference and the timing alike. A non-empty *error stops the run.
    std::function<std::map<std::string, TextureData>(const VariantBuild&, size_t view,
                                                     std::string* error)>
        textures_for;
    // Streaming: with these set, each view's reference image and then each entry's GLSL image of
    // the view (CompareRun::entries index, view index) are handed over as soon as they exist and
    // are not kept (ComparedView::image and CompareRun::reference_images stay empty), so a run
    // holds one view's reference and one variant image at a time, whatever the number of
    // variants and views. Unset: every image is kept in the run.
    std::function<void(const CompareRun&, size_t view, const ImageRGBA32F& reference)> on_reference;
    std::function<void(const CompareRun&, size_t entry, size_t view, const ImageRGBA32F& image,
                       const ImageRGBA32F& reference)>
        on_image;
};

struct ComparedView {
    ImageRGBA32F image;      // GLSL path; empty when streamed (CompareRequest::on_image)
    double glsl_vs_hlsl = 0; // max abs between the two paths (0: bit-identical)
    ImageErrorStats error;   // against the reference image of the view
    // A CPU reference only: pixels whose difference from the reference exceeds what float
    // rounding alone can explain there (|CPU float - double| plus the float error bound,
    // variant_render.h), and the largest such allowance in the view; -1: not measured (GPU
    // reference). The reference variant's own render should have none; an approximation's
    // count is the pixels where it differs as a model.
    int64_t beyond_float_bound = -1;
    double float_bound_max = 0;
};

struct CompareEntry {
    Variant variant;
    bool is_reference = false; // the reference variant itself (GPU reference only)
    // "reference"; "approximates <axis>=<choice>, ..." when every axis where it differs
    // from the reference holds an approximation of the reference's choice (axis registry);
    // else "different model (<axis>: <choice> vs <choice>, ...)".
    std::string relation;
    std::vector<ComparedView> views; // in request order
    RatioInterval time;              // steady draw time / the timing reference's
    double steady_ms = 0;
    size_t spirv_instructions = 0; // optimised fragment SPIR-V, GLSL path
    double cost_per_pixel = 0;     // instructions per pixel under valgrind; 0: not measured
    std::map<std::string, double> target_costs; // AMD target -> ACO fragment instructions / px
};

struct CompareRun {
    std::vector<CompareEntry> entries;
    Variant reference;                          // the reference variant (CPU or GPU)
    bool reference_on_cpu = false;              // CPU double evaluation
    std::vector<ImageRGBA32F> reference_images; // per view; empty when streamed
    RatioInterval aa;                           // timing reference against itself
    double reference_cost_per_pixel = 0;        // the reference variant's instructions per pixel
    double cost_aa = 0; // its count against a second pipeline of it (1: the count is exact)
    bool timing_trustworthy() const { return aa.within(kAATolerance); }
    Diagnostics diagnostics; // of a variant that did not build
    std::string error;       // first failure
    bool ok() const { return error.empty() && !has_errors(diagnostics); }
};

// True when `choice` approximates `target` on `axis`, directly or through a chain of the
// registry's `approximates` (power approximates exact; a 4-step march the converged one).
bool approximates(const AxisInfo& axis, const std::string& choice, const std::string& target);

// The reference a set of variants approximates: the first variant with, on every axis where
// the variants differ, that axis' gold choice where some variant holds the gold or an
// approximation of it (fresnel schlick,power -> exact; waves flat,gerstner stay flat: those
// are different models, not approximations of the converged march).
Variant reference_for(const std::vector<Variant>& variants);

// The relation of `v` to `reference` (see CompareEntry::relation).
std::string relation_to(const Variant& v, const Variant& reference);

// What:   builds every variant and the reference, renders each over every view on both
//         language paths, compares each GLSL image with the reference's, and times the
//         variants interleaved against the reference variant on the GPU in the first view.
// Cost:   a pipeline per variant, view and path (JIT 0.1-0.5 s each on lavapipe), the
//         timing rounds, and one CPU double evaluation per view for a CPU reference.
CompareRun run_compare(VulkanRunner& runner, const CompareRequest& request);

} // namespace watergen
