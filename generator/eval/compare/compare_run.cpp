#include "watergen/eval/compare/compare_run.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "watergen/eval/draw/mesh_render.h"
#include "watergen/eval/draw/variant_render.h"
#include "watergen/pipeline/variant/variant_build.h"

namespace watergen {

namespace {

double max_abs_difference(const std::vector<float>& a, const std::vector<float>& b) {
    if (a.size() != b.size()) return INFINITY;
    double m = 0;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i] != b[i]) // NaN in one and not the other counts as infinite
            m = std::max(m, std::isnan(a[i]) != std::isnan(b[i])
                                ? INFINITY
                                : std::fabs(double(a[i]) - double(b[i])));
    return m;
}

} // namespace

bool approximates(const AxisInfo& axis, const std::string& choice, const std::string& target) {
    std::string at = choice;
    for (size_t hops = 0; hops < axis.choices.size(); ++hops) {
        const ChoiceInfo* c = find_choice(axis, at);
        if (!c || c->approximates.empty()) return false;
        if (c->approximates == target) return true;
        at = c->approximates;
    }
    return false;
}

Variant reference_for(const std::vector<Variant>& variants) {
    if (variants.empty()) return default_variant();
    Variant ref = variants.front();
    const auto& list = axes();
    for (size_t a = 0; a < list.size(); ++a) {
        const bool varies = std::any_of(variants.begin(), variants.end(), [&](const Variant& v) {
            return v.choices[a] != variants.front().choices[a];
        });
        if (!varies) continue;
        // The gold, where some variant holds it or an approximation of it (for choices that
        // are only different models, the first variant's choice stays).
        for (const ChoiceInfo& c : list[a].choices)
            if (c.gold && std::any_of(variants.begin(), variants.end(), [&](const Variant& v) {
                    return v.choices[a] == c.name || approximates(list[a], v.choices[a], c.name);
                }))
                ref.choices[a] = c.name;
    }
    return ref;
}

std::string relation_to(const Variant& v, const Variant& reference) {
    const auto& list = axes();
    std::string approx, different;
    for (size_t a = 0; a < list.size(); ++a) {
        const std::string& mine = v.choices[a];
        const std::string& theirs = reference.choices[a];
        if (mine == theirs) continue;
        if (approximates(list[a], mine, theirs))
            approx += (approx.empty() ? "" : ", ") + list[a].name + "=" + mine;
        else
            different +=
                (different.empty() ? "" : ", ") + list[a].name + ": " + mine + " vs " + theirs;
    }
    if (!different.empty()) return "different model (" + different + ")";
    if (!approx.empty()) return "approximates (" + approx + ")";
    return "reference";
}

namespace {

// The stages of one comparison; `order` holds the reference first, then the other variants, and
// entries[k] is order[first + k] (first = 0 when the reference is one of the compared variants).
class Comparison {
  public:
    Comparison(VulkanRunner& runner, const CompareRequest& request, CompareRun& run)
        : runner_(runner), request_(request), run_(run) {}

    bool build() {
        run_.reference_on_cpu = !request_.reference.has_value();
        run_.reference =
            request_.reference ? *request_.reference : reference_for(request_.variants);
        order_ = {run_.reference};
        for (const Variant& v : request_.variants)
            if (std::none_of(order_.begin(), order_.end(),
                             [&](const Variant& o) { return o.key() == v.key(); }))
                order_.push_back(v);
        for (const Variant& v : order_) {
            builds_.push_back(request_.build ? request_.build(v)
                                             : build_variant(v, request_.preset));
            if (!builds_.back().ok()) {
                run_.diagnostics = builds_.back().diagnostics;
                run_.error = v.key() + ": did not build";
                return false;
            }
        }
        // A mesh reference is measured as the exact surface it approximates.
        cpu_fragment_ = builds_[0].shader.fragment;
        if (run_.reference_on_cpu && draws_mesh(builds_[0].languages[0]))
            cpu_fragment_ = request_.exact_surface
                                ? request_.exact_surface(run_.reference)
                                : exact_surface_fragment(preset_material(request_.preset), nullptr,
                                                         run_.reference);
        const bool listed =
            std::any_of(request_.variants.begin(), request_.variants.end(),
                        [&](const Variant& v) { return v.key() == run_.reference.key(); });
        first_ = listed ? 0 : 1;
        for (size_t i = first_; i < order_.size(); ++i) {
            CompareEntry e;
            e.variant = order_[i];
            e.is_reference = i == 0 && !run_.reference_on_cpu;
            e.relation = relation_to(order_[i], run_.reference);
            e.spirv_instructions =
                builds_[i].languages[0].fragment.toolchain.instruction_count_optimized;
            run_.entries.push_back(std::move(e));
        }
        return true;
    }

    // View `view`'s scene as variant i sees it (request.textures_for); nullptr after a failure.
    const SyntheticScene* scene_for(size_t i, size_t view, const SyntheticScene& scene) {
        if (!request_.textures_for) return &scene;
        std::string error;
        auto textures = request_.textures_for(builds_[i], view, &error);
        if (!error.empty()) {
            run_.error = order_[i].key() + ": " + error;
            return nullptr;
        }
        if (textures.empty()) return &scene;
        own_scene_ = scene;
        for (auto& [name, texture] : textures)
            own_scene_.textures[name] = std::move(texture);
        return &own_scene_;
    }

    // Build i's GLSL image of one view (view 0: the timing's last draw when there is one), its
    // HLSL image compared with it; false after a failure.
    bool render_one(size_t i, size_t view, const std::string& name,
                    const SyntheticScene& view_scene, ImageRGBA32F& image, double& paths_differ) {
        const SyntheticScene* scene = scene_for(i, view, view_scene);
        if (!scene) return false;
        const RenderSettings settings = settings_of(*scene);
        std::array<RenderResult, 2> paths;
        for (size_t l = 0; l < (request_.both_paths ? 2u : 1u); ++l) {
            // View 0's GLSL images are the timing's last draws (read back already); each is
            // moved out when used, so none outlives its turn.
            if (l == 0 && view == 0 && i < timed_.size() && !timed_[i].rgba.empty()) {
                paths[0] = std::move(timed_[i]);
                timed_[i] = RenderResult{};
                continue;
            }
            paths[l] = runner_.render(make_render_job(builds_[i].languages[l], *scene, settings));
            if (!paths[l].ok) {
                run_.error = order_[i].key() + " (" + name + "): " + paths[l].error;
                return false;
            }
        }
        paths_differ = request_.both_paths ? max_abs_difference(paths[0].rgba, paths[1].rgba) : 0.0;
        image = ImageRGBA32F{scene->width, scene->height, std::move(paths[0].rgba)};
        return true;
    }

    // How a view's scene is drawn: at its size, no timing or CPU pass, a mesh over the
    // request's grid.
    RenderSettings settings_of(const SyntheticScene& scene) const {
        RenderSettings s{scene.width, scene.height, 0, false, false};
        s.grid = request_.grid;
        return s;
    }

    // The reference image of a view: the CPU double evaluation, or build 0's GLSL render (with
    // its path difference, for when it is also entry 0).
    bool reference_image(size_t view, const std::string& name, const SyntheticScene& view_scene,
                         ImageRGBA32F& reference, double& paths_differ) {
        if (!run_.reference_on_cpu)
            return render_one(0, view, name, view_scene, reference, paths_differ);
        const SyntheticScene* scene = scene_for(0, view, view_scene);
        if (!scene) return false;
        const EvalResult d = evaluate_image(cpu_fragment_, "color", scene->eval_inputs(),
                                            scene->width, scene->height, EvalPrecision::Double);
        if (!d.ok()) {
            run_.error = "CPU reference (" + name + "): " + d.error;
            return false;
        }
        reference = to_image(d, scene->width, scene->height);
        // What float rounding alone can move a pixel by: the CPU float image's own distance
        // from double, plus how far another float evaluation may be from it.
        const EvalResult f = evaluate_image(cpu_fragment_, "color", scene->eval_inputs(),
                                            scene->width, scene->height, EvalPrecision::Float);
        std::string error = f.error;
        if (error.empty())
            bound_ = float_bound(cpu_fragment_, scene->eval_inputs(), scene->width, scene->height,
                                 d, error, &f);
        if (!error.empty()) {
            run_.error = "CPU reference (" + name + "): " + error;
            return false;
        }
        return true;
    }

    // The pixels of `image` further from `reference` than bound_ allows (a CPU reference).
    void check_float_bound(const ImageRGBA32F& image, const ImageRGBA32F& reference,
                           ComparedView& compared) const {
        if (bound_.empty()) return;
        const Agreement a = check_agreement(image, reference, bound_, 0.0);
        compared.beyond_float_bound = static_cast<int64_t>(a.over_bound);
        compared.float_bound_max = a.max_bound;
    }

    // Every variant on both paths in one view, each GLSL image against the reference's: the
    // reference first, then one variant at a time (streamed to request.on_image, or kept).
    bool render_view(size_t view, const std::string& name, const SyntheticScene& view_scene) {
        const bool streamed = bool(request_.on_image);
        ImageRGBA32F reference;
        double reference_paths = 0;
        if (!reference_image(view, name, view_scene, reference, reference_paths)) return false;
        if (request_.on_reference) request_.on_reference(run_, view, reference);
        for (size_t k = 0; k < run_.entries.size(); ++k) {
            const size_t i = first_ + k;
            ComparedView compared;
            ImageRGBA32F image;
            if (i == 0 && !run_.reference_on_cpu) { // the GPU reference itself
                image = reference;
                compared.glsl_vs_hlsl = reference_paths;
            } else if (!render_one(i, view, name, view_scene, image, compared.glsl_vs_hlsl)) {
                return false;
            }
            compared.error = compare_images(image, reference);
            check_float_bound(image, reference, compared);
            if (streamed)
                request_.on_image(run_, k, view, image, reference);
            else
                compared.image = std::move(image);
            run_.entries[k].views.push_back(std::move(compared));
        }
        if (!streamed) run_.reference_images.push_back(std::move(reference));
        timed_ = {}; // view 0's timed images not used (a CPU reference's build) go too
        return true;
    }

    // Draw times in view 0, every variant against the reference variant on the GPU.
    bool time(const SyntheticScene& view_scene) {
        std::vector<RenderJob> jobs;
        for (size_t i = 0; i < builds_.size(); ++i) {
            const SyntheticScene* scene = scene_for(i, 0, view_scene);
            if (!scene) return false;
            jobs.push_back(make_render_job(builds_[i].languages[0], *scene, settings_of(*scene)));
        }
        InterleavedTiming t = time_interleaved(runner_, jobs, request_.rounds, request_.draws);
        if (!t.ok()) {
            run_.error = "timing: " + t.error;
            return false;
        }
        run_.aa = t.aa;
        for (size_t k = 0; k < run_.entries.size(); ++k) {
            run_.entries[k].time = t.ratios[first_ + k];
            run_.entries[k].steady_ms = t.results[first_ + k].steady_draw_ms;
        }
        // Per build (the A/A copy is not among them); without every image, view 0 renders afresh.
        if (std::all_of(t.results.begin(), t.results.end(),
                        [](const RenderResult& r) { return !r.rgba.empty(); }))
            timed_ = std::move(t.results);
        return true;
    }

  private:
    VulkanRunner& runner_;
    const CompareRequest& request_;
    CompareRun& run_;
    std::vector<Variant> order_;
    std::vector<VariantBuild> builds_;
    Graph cpu_fragment_; // what a CPU reference evaluates (the exact surface of a mesh)
    size_t first_ = 0;
    SyntheticScene own_scene_;        // scene_for's copy with a variant's own textures
    std::vector<float> bound_;        // the view's float allowance per pixel (a CPU reference)
    std::vector<RenderResult> timed_; // time()'s results, per build: view 0's GLSL images
};

} // namespace

CompareRun run_compare(VulkanRunner& runner, const CompareRequest& request) {
    CompareRun run;
    if (request.views.empty()) {
        run.error = "no view to render";
        return run;
    }
    Comparison c(runner, request, run);
    if (!c.build()) return run;
    // Timing first: its last draws are view 0's GLSL images, so no pipeline is made twice.
    if (!c.time(request.views.front().second)) return run;
    for (size_t v = 0; v < request.views.size(); ++v)
        if (!c.render_view(v, request.views[v].first, request.views[v].second)) return run;
    return run;
}

} // namespace watergen
