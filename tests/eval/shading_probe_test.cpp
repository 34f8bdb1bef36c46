// Every node of the fresnel (power), extinction, specular and foam axes at the stress ranges of
// water-models.md through the probe harness: lavapipe (GLSL and HLSL paths) and the CPU in
// double, float and half. Prints the measured gaps; asserts no NaN/Inf, the documented output
// ranges, and GPU = CPU float within stated tolerances.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>

#include "shared_runner.h"
#include "watergen/eval/probe/probe.h"
#include "watergen/water/node_catalog.h"
#include "watergen/water/nodes.h"

using namespace watergen;

namespace {

using Uniforms = std::map<std::string, std::vector<double>>;

ProbeRun probe_graph_on(const Graph& g, Language lang, const std::vector<double>& inputs,
                        const Uniforms& uniforms) {
    return test::checked_probe(g, lang, inputs, uniforms);
}

// Per-component bounds of one output value, and the tolerances of the comparisons.
struct Expect {
    std::function<std::pair<double, double>(size_t tuple, int component)> range;
    double half_slack = 0;   // half may leave the range by this much (absolute)
    double gpu_relative = 0; // |gpu - cpu float| <= gpu_relative |cpu float| + gpu_absolute
    double gpu_absolute = 0;
};

struct Gaps {
    double gpu_float = 0, gpu_float_relative = 0, half_double = 0;
    size_t non_finite = 0, values = 0;
};

// Checks one run; returns the measured gaps.
Gaps check_run(const ProbeRun& run, const Expect& e) {
    Gaps gaps;
    const size_t stride = run.layout.output_stride;
    for (size_t t = 0; t < run.tuples; ++t)
        for (size_t c = 0; c < stride; ++c) {
            const size_t i = t * stride + c;
            const auto [lo, hi] = e.range(t, static_cast<int>(c));
            INFO("tuple " << t << " component " << c << ": gpu " << run.gpu[i] << " double "
                          << run.cpu_double[i] << " float " << run.cpu_float[i] << " half "
                          << run.cpu_half[i]);
            for (const auto* values : {&run.gpu, &run.cpu_double, &run.cpu_float, &run.cpu_half}) {
                const double v = (*values)[i];
                ++gaps.values;
                if (!std::isfinite(v)) ++gaps.non_finite;
                CHECK(std::isfinite(v));
                // Inputs and parameters reach the GPU as floats (0.2 is 0.200000003), and so the
                // CPU.
                const double slack = (values == &run.cpu_half ? e.half_slack : 0.0) +
                                     1e-7 * std::max(1.0, std::fabs(hi));
                CHECK(v >= lo - slack);
                CHECK(v <= hi + slack);
            }
            const double gap = std::fabs(run.gpu[i] - run.cpu_float[i]);
            CHECK(gap <= e.gpu_relative * std::fabs(run.cpu_float[i]) + e.gpu_absolute);
            gaps.gpu_float = std::max(gaps.gpu_float, gap);
            if (std::fabs(run.cpu_float[i]) > 1e-3)
                gaps.gpu_float_relative =
                    std::max(gaps.gpu_float_relative, gap / std::fabs(run.cpu_float[i]));
            if (std::isfinite(run.cpu_half[i] - run.cpu_double[i]))
                gaps.half_double =
                    std::max(gaps.half_double, std::fabs(run.cpu_half[i] - run.cpu_double[i]));
        }
    return gaps;
}

void report(const std::string& what, Language lang, const Gaps& g) {
    std::printf("%-44s %-4s values %5zu  NaN/Inf %zu  max|gpu-cpu float| %.3g (rel %.3g where > "
                "1e-3)  max|half-double| %.3g\n",
                what.c_str(), to_string(lang), g.values, g.non_finite, g.gpu_float,
                g.gpu_float_relative, g.half_double);
}

void probe_node(const std::string& node, const std::vector<double>& inputs, const Expect& e,
                const Uniforms& uniforms = {}, const std::string& label = "",
                const std::function<void(const ProbeRun&)>& also = {}) {
    const CatalogNode* n = find_catalog_node(node);
    REQUIRE(n != nullptr);
    const Graph g = probe_graph(*n);
    for (Language lang : {Language::Glsl, Language::Hlsl}) {
        INFO(node << " " << label << " " << to_string(lang));
        const ProbeRun run = probe_graph_on(g, lang, inputs, uniforms);
        report(node + " " + label, lang, check_run(run, e));
        if (also) also(run);
    }
}

// water-models.md stress sets.
const std::vector<double> kDistances = {-1e-3, 0,   1e-6, 0.1,  10,      21.1,
                                        190,   1e3, 1e4,  1e30, INFINITY};
const std::vector<double> kCosines = {
    -1, -1e-7, 0, 1e-7, 1e-3, 0.5, 1 - std::ldexp(1.0, -24), 1, 1 + std::ldexp(1.0, -23)};
const std::vector<double> kPowBases = {0, 1e-38, 1e-7, 0.5, 0.98, 1};
const std::vector<double> kPowExponents = {1e-6, 4.5, 5, 512, 4096};

const std::array<std::array<double, 3>, 2> kRefractions = {{{0.5, 0.5, 0.5}, {0.9, 0.3, 0.0}}};

std::vector<double> extinction_tuples() {
    std::vector<double> t;
    for (const auto& refr : kRefractions)
        for (double depth : kDistances)
            for (double path : kDistances)
                t.insert(t.end(), {depth, path, refr[0], refr[1], refr[2]});
    return t;
}

// Refraction colour of extinction tuple t.
double refraction_of(size_t t, int c) {
    return kRefractions[t / (kDistances.size() * kDistances.size())][c];
}

std::pair<double, double> hull(std::initializer_list<double> values) {
    return {std::min(values), std::max(values)};
}

using V3 = std::array<double, 3>;
V3 unit(V3 a) {
    const double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    return {a[0] / l, a[1] / l, a[2] / l};
}

// (normal, to_eye, sun_direction, fresnel) tuples: the stress configurations (sun at zenith,
// on the horizon, below it (harbour at night), L = -V and L = V, N.V <= 0, a zero normal from
// a normal-map texel decoding to zero, grazing views) and 2000 random lit configurations.
std::vector<double> specular_tuples() {
    std::vector<double> t;
    auto add = [&](const V3& n, const V3& v, const V3& l, double f) {
        t.insert(t.end(), {n[0], n[1], n[2], v[0], v[1], v[2], l[0], l[1], l[2], f});
    };
    const std::vector<V3> normals = {
        {0, 1, 0}, unit({0.3, 0.9, 0.1}), unit({1, 1e-3, 0}), {0, 0, 0}, unit({0, 0.2, -1})};
    const std::vector<V3> eyes = {{0, 1, 0},
                                  unit({0, 0.6, 0.8}),
                                  unit({0, 1e-3, 1}),
                                  unit({0, 1e-7, 1}),
                                  unit({0, -0.6, 0.8})};
    const std::vector<V3> suns = {{0, -1, 0},       {0, 0, 1},
                                  {1, 0, 0},        unit({0, -1e-3, 1}),
                                  {0.2, 0.3, 0.93}, unit({-0.35, -0.75, 0.55})};
    for (const V3& n : normals)
        for (const V3& v : eyes) {
            std::vector<V3> ls = suns;
            ls.push_back({-v[0], -v[1], -v[2]}); // L = -V: the sun behind the eye
            ls.push_back(v);                     // L = V: -L + V = 0
            ls.push_back({v[0], -v[1], v[2]});   // the mirror direction over a flat surface
            for (const V3& l : ls)
                for (double f : {0.0, 0.0204, 0.5, 1.0})
                    add(n, v, l, f);
        }
    std::mt19937 rng(777);
    auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * (rng() / 4294967296.0); };
    for (int i = 0; i < 2000; ++i) {
        const V3 n = unit({uniform(-0.3, 0.3), 1, uniform(-0.3, 0.3)});
        const V3 v = unit({uniform(-1, 1), uniform(0.05, 1), uniform(-1, 1)});
        // Half of them near the mirror direction, where the lobes are large.
        const V3 mirror = {2 * (n[0] * v[0] + n[1] * v[1] + n[2] * v[2]) * n[0] - v[0],
                           2 * (n[0] * v[0] + n[1] * v[1] + n[2] * v[2]) * n[1] - v[1],
                           2 * (n[0] * v[0] + n[1] * v[1] + n[2] * v[2]) * n[2] - v[2]};
        const V3 l = i % 2 ? unit({uniform(-1, 1), uniform(-1, -0.02), uniform(-1, 1)})
                           : unit({-mirror[0] + uniform(-0.05, 0.05), -mirror[1],
                                   -mirror[2] + uniform(-0.05, 0.05)});
        add(n, v, l, uniform(0, 1));
    }
    return t;
}

} // namespace

TEST_CASE("extinction_nodes_survive_the_stress_distances_on_gpu_and_cpu",
          "[probe][stress][extinction]") {
    const auto tuples = extinction_tuples();
    const double surface[3] = {0.0078, 0.5176, 0.7}, deep[3] = {0.0039, 0.00196, 0.145},
                 water[3] = {0.0, 0.2, 0.1};
    // Outputs are convex combinations of the colours involved (or refr times a transmittance in
    // [0, 1]). Half: a mix may land one binary16 ulp of 1 (2^-11) outside. GPU: exp on lavapipe
    // is not correctly rounded; relative 2e-6 (as absorb_scatter) and 1e-7 absolute.
    Expect linear{[&](size_t t, int c) {
                      return hull({refraction_of(t, c), surface[c], deep[c]});
                  },
                  0x1p-11, 2e-6, 1e-7};
    // ext and visibility at the stress set {0, 1e-6, 4.5, 1e6} m.
    for (double d : {0.0, 1e-6, 4.5, 1e6})
        probe_node("extinction.linear", tuples, linear,
                   {{"extinction_distances", {d, d, d}}, {"extinction_visibility", {d}}},
                   "ext=visibility=" + std::to_string(d));
    probe_node("extinction.exponential", tuples,
               {[&](size_t t, int c) {
                    return hull({refraction_of(t, c), water[c]});
                },
                0x1p-11, 2e-6, 1e-7});
    probe_node("extinction.beer_lambert", tuples,
               {[&](size_t t, int c) {
                    return hull({0.0, refraction_of(t, c)});
                },
                0x1p-11, 2e-6, 1e-7});
}

TEST_CASE("fresnel_power_survives_the_stress_cosines_on_gpu_and_cpu", "[probe][stress][fresnel]") {
    // pow on lavapipe is exp2(q log2 x): relative 2e-6 measured headroom.
    probe_node("fresnel.power", kCosines,
               {[](size_t, int) {
                    return std::pair{0.0, 1.0};
                },
                0.0, 2e-6, 1e-7});
}

TEST_CASE("specular_nodes_survive_the_stress_configurations_on_gpu_and_cpu",
          "[probe][stress][specular]") {
    const auto tuples = specular_tuples();
    // A sun at or below the horizon (travelling level or upwards) adds exactly nothing.
    const auto dark_below_horizon = [&](const ProbeRun& run) {
        size_t checked = 0;
        for (size_t t = 0; t < run.tuples; ++t)
            if (tuples[t * 10 + 7] >= 0.0) {
                ++checked;
                CHECK((run.gpu[t] == 0.0 && run.cpu_float[t] == 0.0 && run.cpu_half[t] == 0.0 &&
                       run.cpu_double[t] == 0.0));
            }
        CHECK(checked > 100);
    };
    // toman_glare: [0, (1.8 s + 0.2)(1 + 25 (s - 0.05))] = [0, 25.185] at s = 0.7. Half rounds
    // the constants and the product: 2^-10 relative. GPU: the lobe is 1 - y with y computed
    // without cancellation (specular.cpp); the final subtraction carries one ulp of 1 times the
    // peak: 25.185 x 2^-23 = 3e-6 absolute, 1e-5 relative stated.
    const double toman_peak = (0.7 * 1.8 + 0.2) * (1 + 25 * 0.65);
    probe_node("specular.toman_glare", tuples,
               {[&](size_t, int) {
                    return std::pair{0.0, toman_peak};
                },
                toman_peak * 0x1p-10, 1e-5, toman_peak * 0x1p-23},
               {}, "", dark_below_horizon);
    // blinn_phong: [0, 1]; pow(N.H, 256) amplifies N.H's relative error 256 times.
    probe_node("specular.blinn_phong", tuples,
               {[](size_t, int) {
                    return std::pair{0.0, 1.0};
                },
                0.0, 1e-4, 1e-6},
               {}, "", dark_below_horizon);
    // ggx_sun: D <= 1 / (pi a^2), masking <= 1 / a, F <= 1: [0, 1 / (pi a^3)]. Half: the lobe
    // near its peak is within 3 % (see specular_optics_test), so 3 % of the bound.
    for (double a : {0.3, 0.0}) {
        const double alpha = std::max(a, 0.02);
        const double bound = 1.0 / (M_PI * alpha * alpha * alpha);
        probe_node("specular.ggx_sun", tuples,
                   {[&](size_t, int) {
                        return std::pair{0.0, bound};
                    },
                    0.03 * bound, 1e-5, 1e-6},
                   {{"specular_roughness", {a}}}, "roughness=" + std::to_string(a),
                   dark_below_horizon);
    }
}

TEST_CASE("specular_lobe_survives_the_stress_pow_grid_on_gpu_and_cpu",
          "[probe][stress][specular]") {
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    Expr s = varying(g, "s", Type::Float);
    {
        RelaxedScope relaxed(g, true);
        g.set_output("value", specular_lobe(x, s).id());
    }
    std::vector<double> tuples;
    for (double base : kPowBases)
        for (double e : kPowExponents)
            tuples.insert(tuples.end(), {base, e});
    for (double base : kPowBases)
        tuples.insert(tuples.end(), {base, 0.0}); // pow(0, 0) territory
    for (Language lang : {Language::Glsl, Language::Hlsl}) {
        INFO(to_string(lang));
        const ProbeRun run = probe_graph_on(g, lang, tuples, {});
        // pow on lavapipe: relative 1e-5 (4096 x log2 error), absolute 1e-7.
        report("specular_lobe(x, s)", lang,
               check_run(run, {[](size_t, int) {
                                   return std::pair{0.0, 1.0};
                               },
                               0.0, 1e-5, 1e-7}));
        // Bases below 2^-14 (0, the denormal 1e-38 a GPU flushes, 1e-7) give 0 everywhere.
        for (size_t t = 0; t < run.tuples; ++t) {
            const double base = tuples[t * 2];
            if (base < 0x1p-14)
                CHECK((run.gpu[t] == 0.0 && run.cpu_float[t] == 0.0 && run.cpu_half[t] == 0.0));
        }
    }
}

TEST_CASE("microfacet_distributions_survive_the_stress_cosines_on_gpu_and_cpu",
          "[probe][stress][specular]") {
    Graph g;
    Expr ch = varying(g, "ch", Type::Float);
    Expr a = varying(g, "alpha", Type::Float);
    {
        RelaxedScope relaxed(g, true);
        g.set_output("beckmann", beckmann_distribution(ch, a).id());
        g.set_output("ggx", ggx_distribution(ch, a).id());
    }
    std::vector<double> tuples;
    const std::vector<double> alphas = {0.02, 0.3, 1.0};
    for (double c : kCosines)
        for (double alpha : alphas)
            tuples.insert(tuples.end(), {c, alpha});
    for (Language lang : {Language::Glsl, Language::Hlsl}) {
        INFO(to_string(lang));
        const ProbeRun run = probe_graph_on(g, lang, tuples, {});
        // Both peak at 1 / (pi a^2) (ch = 1). Half: 2^-10 relative of the peak.
        const auto range = [&](size_t t, int) {
            return std::pair{0.0, 1.0 / (M_PI * tuples[t * 2 + 1] * tuples[t * 2 + 1])};
        };
        report("beckmann / ggx D(ch, a)", lang, check_run(run, {range, 800 * 0x1p-10, 1e-5, 1e-6}));
    }
}

TEST_CASE("foam_nodes_survive_the_stress_depths_and_heights_on_gpu_and_cpu",
          "[probe][stress][foam]") {
    const std::vector<double> heights = {-INFINITY, -1e4, -1.0, 0.0,  1.5,
                                         2.25,      3.0,  1e4,  1e30, INFINITY};
    const std::vector<double> patterns = {0.0, 0.2, 1.0};
    const double color[3] = {0.2, 0.4, 0.6};
    std::vector<double> tuples;
    for (double p : patterns)
        for (double depth : kDistances)
            for (double h : heights)
                tuples.insert(tuples.end(), {color[0], color[1], color[2], p, depth, h});
    const size_t per_pattern = kDistances.size() * heights.size();
    // mix(colour, foam_color pattern, f) with f in [0, 1] and foam colour 1: between the two.
    // Half: one binary16 ulp of 1 (2^-11) outside. GPU: only + - * / select: 4e-7.
    const Expect e{[&](size_t t, int c) {
                       return hull({color[c], patterns[t / per_pattern]});
                   },
                   0x1p-11, 0.0, 4e-7};
    probe_node("foam.shore", tuples, e);
    probe_node("foam.crest", tuples, e);
    probe_node("foam.both", tuples, e);
    // Guards: Hmax <= h0 + e.z, and e.y <= e.x.
    probe_node("foam.both", tuples, e, {{"foam_max_height", {1.5}}}, "Hmax=e.z");
    probe_node("foam.both", tuples, e,
               {{"foam_existence", {1.0, 1.0, 1.5}}, {"foam_max_height", {0.0}}}, "e.y=e.x,Hmax=0");
}
