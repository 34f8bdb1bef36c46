#include "watergen/render/accuracy_bench.h"

#include <optional>

#include <fmt/format.h>

#include "watergen/ir/cpu_evaluator.h"
#include "watergen/pipeline/variant_build.h"
#include "watergen/plan/variant_space.h"
#include "watergen/render/synthetic_scene.h"

namespace watergen {

Variant accuracy_reference_variant() {
    Variant v = default_variant();
    for (const auto& a : axes())
        for (const auto& c : a.choices)
            if (c.gold) set_choice(v, a.name, c.name);
    set_choice(v, "waves", "gerstner"); // analytic normals need a closed-form wave model
    return v;
}

namespace {

// One axis measured: its gold first, so every other row compares against it.
class AxisMeasure {
  public:
    AxisMeasure(VulkanRunner& runner, const SyntheticScene& scene, const RenderSettings& settings,
                AccuracyBench& out)
        : runner_(runner), scene_(scene), settings_(settings), out_(out) {}

    // False at the first failure (recorded in the bench).
    bool run(const AxisInfo& axis, const ChoiceInfo& gold) {
        Variant base = accuracy_reference_variant();
        if (axis.name == "waves")
            set_choice(base, "normals", "detail_map"); // valid for every wave model
        if (!measure(axis, gold, base)) return false;
        for (const auto& c : axis.choices)
            if (&c != &gold && !measure(axis, c, base)) return false;
        return true;
    }

  private:
    bool measure(const AxisInfo& axis, const ChoiceInfo& choice, const Variant& base) {
        Variant v = base;
        set_choice(v, axis.name, choice.name);
        AccuracyRow row;
        row.axis = axis.name;
        row.choice = choice.name;
        row.gold = choice.gold;
        if (auto e = check_constraints(v)) {
            row.note = "skipped: " + *e;
            out_.rows.push_back(row);
            return true;
        }
        // A half row renders in 16-bit arithmetic (strict half): lavapipe runs mediump at 32.
        const bool half = axis.name == "precision" && !choice.gold;
        const VariantBuild build = build_variant(v, nullptr, EmitOptions{half});
        if (!build.ok()) {
            out_.diagnostics = build.diagnostics;
            return false;
        }
        VariantRender r = render_variant(runner_, build, scene_, settings_);
        if (!r.ok()) {
            out_.error = v.key() + ": " + r.error;
            return false;
        }
        row.steady_ms = r.gpu[0].steady_draw_ms;
        row.instructions = build.languages[0].fragment.toolchain.instruction_count_optimized;
        if (choice.gold) {
            gold_render_ = std::move(r);
            gold_build_ = build;
            row.time_ratio = 1.0;
            row.error = compare_images(gold_render_.gpu_image[0], gold_render_.gpu_image[0]);
        } else {
            // The gold is timed again right after each candidate: this machine's speed
            // drifts, and a ratio of back-to-back medians cancels most of that.
            const VariantRender again = render_variant(runner_, *gold_build_, scene_, settings_);
            row.time_ratio = row.steady_ms / (again.ok() ? again.gpu[0].steady_draw_ms
                                                         : gold_render_.gpu[0].steady_draw_ms);
            row.error = compare_images(r.gpu_image[0], gold_render_.gpu_image[0]);
        }
        if (half) {
            const EvalResult emulated =
                evaluate_image(build.shader.fragment, "color", scene_.eval_inputs(),
                               settings_.width, settings_.height, EvalPrecision::Half);
            const ImageErrorStats cpu = compare_images(
                to_image(emulated, settings_.width, settings_.height), gold_render_.gpu_image[0]);
            row.note = fmt::format("strict half: 16-bit arithmetic on the GPU (GLSL) vs full; the "
                                   "CPU half model predicts max abs {:.3g}, dE p99 {:.3f}",
                                   cpu.max_abs, cpu.ciede2000_p99);
        }
        out_.rows.push_back(row);
        return true;
    }

    VulkanRunner& runner_;
    const SyntheticScene& scene_;
    const RenderSettings& settings_;
    AccuracyBench& out_;
    VariantRender gold_render_;
    std::optional<VariantBuild> gold_build_;
};

} // namespace

AccuracyBench run_accuracy_bench(VulkanRunner& runner, uint32_t size, uint32_t draws) {
    const SyntheticScene scene = make_synthetic_scene(size, size);
    const RenderSettings settings{size, size, draws, true};
    AccuracyBench bench;
    for (const auto& axis : axes()) {
        const ChoiceInfo* gold = nullptr;
        for (const auto& c : axis.choices)
            if (c.gold) gold = &c;
        if (gold && !AxisMeasure(runner, scene, settings, bench).run(axis, *gold)) break;
    }
    return bench;
}

} // namespace watergen
