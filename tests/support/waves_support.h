// Helpers of the wave and normal tests: catalog nodes on the CPU, and the formulas of the
// seeds written out in double for golden values.
#pragma once

#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "watergen/eval/scene/scene_wave_inputs.h"
#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/ir/emit/emitter.h"
#include "watergen/water/node_catalog.h"

namespace watergen::test {

using Uniforms = std::map<std::string, std::vector<double>>;

// The catalog node `name` on the CPU for tuples laid out as its inputs (tuple-major), with
// the synthetic scene's wave textures. Lanes are in order, so 2x2 quads are lanes 4k..4k+3.
inline EvalResult eval_node(const std::string& name, const std::vector<double>& tuples,
                            EvalPrecision precision, const Uniforms& uniforms = {},
                            const std::map<std::string, TextureData>* textures = nullptr) {
    const CatalogNode* node = find_catalog_node(name);
    if (!node) throw std::runtime_error("no catalog node " + name);
    const Graph g = probe_graph(*node);
    const ProbeLayout layout = probe_layout(g);
    EvalInputs in;
    in.uniforms = uniforms;
    in.lanes = tuples.size() / layout.input_stride;
    for (const auto& f : layout.inputs) {
        auto& v = in.varyings[f.name];
        for (size_t t = 0; t < in.lanes; ++t)
            for (int c = 0; c < component_count(f.type); ++c)
                v.push_back(tuples[t * layout.input_stride + f.offset + c]);
    }
    static const std::map<std::string, TextureData> scene_textures = {
        {"height_map", make_height_map()}, {"detail_normal_map", make_detail_normal_map()}};
    if (!textures) textures = &scene_textures;
    for (const auto& [tex_name, t] : *textures)
        in.textures[tex_name] = TextureView{t.width, t.height, t.rgba.data()};
    in.filter = Filter::Linear;
    EvalResult r = evaluate(g, "value", in, precision);
    if (!r.ok()) throw std::runtime_error(name + ": " + r.error);
    return r;
}

// ---- 004 in double, with the parameter defaults of water/nodes/wave_families.cpp ----

struct WaveModel {
    double amplitude, frequency, amplitude_gain = 0.82, frequency_gain = 1.18;
    std::array<double, 16> directions; // (x, z) per wave
    std::array<double, 8> phase_speeds;
    double steepness = 0.5; // Gerstner only
    int count = 4;          // <family>_wave_count

    double a(int i) const { return amplitude * std::pow(amplitude_gain, i); }
    double f(int i) const { return frequency * std::pow(frequency_gain, i); }
    double dx(int i) const { return directions[2 * i]; }
    double dz(int i) const { return directions[2 * i + 1]; }
    double theta(int i, double x, double z, double t) const {
        return f(i) * (dx(i) * x + dz(i) * z) + t * phase_speeds[i];
    }
    // GPU Gems' Q_i A_i with Q_i = Q / (w_i A_i n).
    double qa(int i) const { return a(i) == 0 ? 0.0 : steepness / (count * f(i) * a(i)) * a(i); }
};

inline WaveModel sines_model() {
    return {0.15,
            0.9,
            0.82,
            1.18,
            {0.28, -0.96, -0.6, -0.8, 0.8, -0.6, -0.96, -0.28, 0.6, -0.8, -0.8, -0.6, 0.96, -0.28,
             -0.28, -0.96},
            {2.97, 3.23, 3.51, 3.81, 4.14, 4.49, 4.88, 5.30}};
}
inline WaveModel gerstner_model() {
    return {0.2,
            0.7,
            0.82,
            1.18,
            {0.0, -1.0, 0.6, -0.8, -0.8, -0.6, 0.96, -0.28, -0.6, -0.8, 0.8, -0.6, -0.28, -0.96,
             0.28, -0.96},
            {2.62, 2.85, 3.09, 3.36, 3.65, 3.96, 4.30, 4.68},
            0.5};
}

// 004: h = sum a_i sin(f_i (d_i . p) + t phi_i).
inline double sines_height(const WaveModel& m, double x, double z, double t) {
    double h = 0;
    for (int i = 0; i < m.count; ++i)
        h += m.a(i) * std::sin(m.theta(i, x, z, t));
    return h;
}

// 004 / GPU Gems: (sum Q_i A_i D_i.x cos, sum A_i sin, sum Q_i A_i D_i.z cos).
inline std::array<double, 3> gerstner_offset(const WaveModel& m, double x, double z, double t) {
    std::array<double, 3> d{0, 0, 0};
    for (int i = 0; i < m.count; ++i) {
        const double th = m.theta(i, x, z, t);
        d[0] += m.qa(i) * m.dx(i) * std::cos(th);
        d[1] += m.a(i) * std::sin(th);
        d[2] += m.qa(i) * m.dz(i) * std::cos(th);
    }
    return d;
}

inline double angle_between(const double* a, const double* b) {
    const double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    const double lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    // atan2 of |a x b| and a . b stays accurate for tiny angles, unlike acos.
    const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                         a[0] * b[1] - a[1] * b[0]};
    return std::atan2(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / (la * lb),
                      d / (la * lb));
}

} // namespace watergen::test
