#include "watergen/ir/cpu/float_error.h"

#include <algorithm>
#include <cmath>

namespace watergen {

namespace {

// The quad holding pixel (x, y), with v_uv at pixel centres as evaluate_image places them;
// `lane` is the pixel's lane in it.
EvalInputs quad_inputs(EvalInputs in, uint32_t width, uint32_t height, uint32_t x, uint32_t y,
                       size_t& lane) {
    std::vector<double> uv(8);
    for (uint32_t i = 0; i < 4; ++i) {
        uv[i * 2 + 0] = (2.0 * (x / 2) + (i & 1) + 0.5) / width;
        uv[i * 2 + 1] = (2.0 * (y / 2) + (i >> 1) + 0.5) / height;
    }
    lane = (x & 1) + 2 * (y & 1);
    in.varyings["v_uv"] = std::move(uv);
    in.lanes = 4;
    in.threads = 1;
    return in;
}

std::vector<double> lane_values(const EvalResult& r, size_t lane) {
    const auto c = static_cast<size_t>(r.components);
    return {r.values.begin() + long(lane * c), r.values.begin() + long((lane + 1) * c)};
}

double max_change(const std::vector<double>& a, const std::vector<double>& b) {
    double m = 0;
    for (size_t c = 0; c < a.size() && c < b.size(); ++c)
        m = std::max(m, std::fabs(a[c] - b[c]));
    return m;
}

} // namespace

PixelAttribution attribute_float_error(const Graph& g, const std::string& output,
                                       const EvalInputs& inputs, uint32_t width, uint32_t height,
                                       uint32_t x, uint32_t y, size_t keep) {
    PixelAttribution a;
    size_t lane = 0;
    EvalInputs in = quad_inputs(inputs, width, height, x, y, lane);
    in.perturbation = {};
    const EvalResult d = evaluate(g, output, in, EvalPrecision::Double);
    const EvalResult f = evaluate(g, output, in, EvalPrecision::Float);
    if (!d.ok() || !f.ok()) {
        a.error = d.ok() ? f.error : d.error;
        return a;
    }
    a.double_value = lane_values(d, lane);
    a.float_value = lane_values(f, lane);
    const std::vector<EvalSite> sites = evaluation_sites(g, output, in);
    // Sites [0, s) rounded, then [0, s + 1): what rounding site s adds to the float rounding
    // of everything before it.
    std::vector<double> before = a.double_value;
    for (size_t s = 0; s < sites.size(); ++s) {
        in.perturbation.round_first = 0;
        in.perturbation.round_end = static_cast<int64_t>(s + 1);
        const EvalResult r = evaluate(g, output, in, EvalPrecision::Double);
        if (!r.ok()) {
            a.error = r.error;
            return a;
        }
        std::vector<double> now = lane_values(r, lane);
        const double change = max_change(now, before);
        if (change > 0) a.effects.push_back({s, sites[s], change});
        before = std::move(now);
    }
    std::stable_sort(a.effects.begin(), a.effects.end(),
                     [](const SiteEffect& p, const SiteEffect& q) { return p.change > q.change; });
    if (a.effects.size() > keep) a.effects.resize(keep);
    return a;
}

ErrorSpread float_error_spread(const Graph& g, const std::string& output, const EvalInputs& inputs,
                               uint32_t width, uint32_t height, const EvalResult& double_image,
                               int runs, double relative) {
    ErrorSpread out;
    out.per_pixel.assign(size_t(width) * height, 0.0f);
    const auto comps = static_cast<size_t>(double_image.components);
    EvalInputs in = inputs;
    for (int run = 0; run < runs; ++run) {
        in.perturbation = {};
        in.perturbation.seed = 0x9e3779b97f4a7c15ull * uint64_t(run + 1);
        in.perturbation.relative = relative;
        const EvalResult r = evaluate_image(g, output, in, width, height, EvalPrecision::Double);
        if (!r.ok()) {
            out.error = r.error;
            return out;
        }
        for (size_t p = 0; p < out.per_pixel.size(); ++p) {
            double m = out.per_pixel[p];
            for (size_t c = 0; c < comps; ++c)
                m = std::max(
                    m, std::fabs(r.values[p * comps + c] - double_image.values[p * comps + c]));
            out.per_pixel[p] = static_cast<float>(m);
        }
    }
    return out;
}

} // namespace watergen
