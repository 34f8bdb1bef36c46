#include "watergen/eval/compare/view_separation.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "watergen/eval/draw/variant_render.h"
#include "watergen/plan/variant_space.h"
#include "watergen/water/axis_registry.h"
#include "watergen/water/water_shader.h"

namespace watergen {

namespace {

// Whether `choice` can stand beside every choice of `axis`.
bool allows_every_choice(const ChoiceInfo& choice, const AxisInfo& axis) {
    for (const auto& r : choice.requirements)
        if (r.axis == axis.name && r.choices.size() < axis.choices.size()) return false;
    return true;
}

ImageDifference difference(const ImageRGBA32F& a, const ImageRGBA32F& b, double threshold) {
    ImageDifference d;
    d.pixels = a.pixel_count();
    for (size_t p = 0; p < d.pixels; ++p) {
        double pixel = 0;
        for (size_t c = 0; c < 3; ++c)
            pixel = std::max(pixel, std::abs(double(a.rgba[p * 4 + c]) - b.rgba[p * 4 + c]));
        d.max_abs = std::max(d.max_abs, pixel);
        if (pixel > threshold) ++d.pixels_over;
    }
    return d;
}

// Every view's scene at one size, and the CPU images of the variants evaluated over it so far.
class ViewImages {
  public:
    explicit ViewImages(uint32_t size) {
        for (const SceneView& v : scene_views())
            scenes_.push_back(make_synthetic_scene(size, size, v));
    }
    size_t views() const { return scenes_.size(); }
    const ImageRGBA32F* image(const Variant& v, size_t view, std::string* error) {
        auto [it, fresh] = images_.try_emplace({v.key(), view});
        if (fresh) it->second = cpu_variant_image(v, scenes_[view], error);
        return it->second.well_formed() && !it->second.rgba.empty() ? &it->second : nullptr;
    }

  private:
    std::vector<SyntheticScene> scenes_;
    std::map<std::pair<std::string, size_t>, ImageRGBA32F> images_;
};

} // namespace

Variant separation_base(const Variant& reference, const std::string& axis_name) {
    Variant base = reference;
    const AxisInfo* axis = find_axis(axis_name);
    if (!axis) return base;
    for (const AxisInfo& other : axes()) {
        const ChoiceInfo* current = find_choice(other, base.choice(other.name));
        if (other.name == axis_name || !current || allows_every_choice(*current, *axis)) continue;
        for (auto c = other.choices.rbegin(); c != other.choices.rend(); ++c)
            if (allows_every_choice(*c, *axis)) {
                set_choice(base, other.name, c->name);
                break;
            }
    }
    return base;
}

ImageRGBA32F cpu_variant_image(const Variant& v, const SyntheticScene& scene, std::string* error) {
    if (auto e = check_constraints(v)) {
        *error = v.key() + ": " + *e;
        return {};
    }
    const WaterShader shader = build_water_shader(v);
    if (has_errors(shader.fragment.diagnostics())) {
        *error = v.key() + ": the shader does not build";
        return {};
    }
    const EvalPrecision precision =
        v.choice("precision") == "half" ? EvalPrecision::Half : EvalPrecision::Float;
    const EvalResult r = evaluate_image(shader.fragment, "color", scene.eval_inputs(), scene.width,
                                        scene.height, precision);
    if (!r.ok()) {
        *error = v.key() + ": " + r.error;
        return {};
    }
    return to_image(r, scene.width, scene.height);
}

ViewSeparation measure_view_separation(const Variant& reference, uint32_t size, double threshold) {
    ViewSeparation out;
    out.size = size;
    out.threshold = threshold;
    ViewImages images(size);
    for (const AxisInfo& axis : axes()) {
        // The CPU evaluates a fragment alone, not a rasterised mesh: the geometry axis' images
        // are held to the exact surface by render_geometry and bench geometry instead.
        if (axis.name == "geometry") continue;
        const Variant base = separation_base(reference, axis.name);
        for (size_t i = 0; i < axis.choices.size(); ++i)
            for (size_t j = i + 1; j < axis.choices.size(); ++j) {
                ChoicePair pair{axis.name, axis.choices[i].name, axis.choices[j].name, base, {}};
                Variant a = base, b = base;
                set_choice(a, axis.name, pair.first);
                set_choice(b, axis.name, pair.second);
                for (size_t view = 0; view < images.views(); ++view) {
                    const ImageRGBA32F* ia = images.image(a, view, &out.error);
                    const ImageRGBA32F* ib = images.image(b, view, &out.error);
                    if (!ia || !ib) return out;
                    pair.views.push_back(difference(*ia, *ib, threshold));
                }
                out.pairs.push_back(std::move(pair));
            }
    }
    return out;
}

std::string view_separation_table(const ViewSeparation& s) {
    std::string out = fmt::format("{:<11} {:<42}", "axis", "choices");
    for (const SceneView& v : scene_views())
        out += fmt::format(" {:>16}", v.name);
    out += fmt::format("\n{:<54}", "");
    for (size_t i = 0; i < scene_views().size(); ++i)
        out += fmt::format(" {:>16}", fmt::format("max abs, >{:g}", s.threshold));
    out += "\n";
    for (const ChoicePair& p : s.pairs) {
        out += fmt::format("{:<11} {:<42}", p.axis, p.first + " / " + p.second);
        for (const ImageDifference& d : p.views)
            out +=
                fmt::format(" {:>9.2g} {:>5.1f}%", d.max_abs,
                            100.0 * double(d.pixels_over) / double(std::max<size_t>(d.pixels, 1)));
        out += "\n";
    }
    return out;
}

} // namespace watergen
