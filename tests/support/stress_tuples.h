// Input tuples for the stress tests of every catalog node: extreme but finite values mixed with
// ordinary ones, from a fixed generator, so a node gets the same tuples on every platform.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "watergen/eval/probe/probe.h"

namespace watergen::test {

constexpr size_t kTuplesPerNode = 256; // whole 2x2 quads, for the nodes that take ddx / ddy

const double kExtreme[] = {0.0, 1e-30, -1e-30, 1e-7, -1e-7, 1.0, -1.0, 1e4, -1e4, 1e30, -1e30};
const double kOrdinary[] = {0.3, -0.6, 0.8, 2.5, -7.0, 12.0, 0.05, -0.25, 100.0, 0.5};
const double kDirectionLength[] = {0.0, 1e-20, 1e20};

// A 64-bit LCG (Knuth's MMIX constants): the same tuples on every platform and library.
struct Lcg {
    uint64_t state;
    uint32_t next(uint32_t n) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<uint32_t>((state >> 33) % n);
    }
    template <size_t N> double pick(const double (&values)[N]) { return values[next(N)]; }
};

// Tuple 0 is all ordinary; every later field is, with equal odds, per-component extreme or
// ordinary values, or (vectors) a zero vector or a direction of length 1e-20 or 1e20 (with an
// ordinary direction), or an ordinary vector.
inline std::vector<double> stress_tuples(const ProbeLayout& layout, uint64_t seed) {
    Lcg rng{seed};
    std::vector<double> tuples;
    for (size_t t = 0; t < kTuplesPerNode; ++t)
        for (const auto& field : layout.inputs) {
            const int n = component_count(field.type);
            const uint32_t kind = t == 0 ? 2 : rng.next(n > 1 ? 4 : 3);
            double v[4];
            for (int c = 0; c < n; ++c)
                v[c] = kind == 0 ? rng.pick(kExtreme) : rng.pick(kOrdinary);
            if (kind == 1 && n == 1) v[0] = rng.pick(kExtreme) * (rng.next(2) ? 1.0 : 0.37);
            if (kind == 3) { // a direction of extreme length
                double len2 = 0;
                for (int c = 0; c < n; ++c)
                    len2 += v[c] * v[c];
                const double scale = rng.pick(kDirectionLength) / std::sqrt(len2);
                for (int c = 0; c < n; ++c)
                    v[c] *= scale;
            }
            tuples.insert(tuples.end(), v, v + n);
        }
    return tuples;
}

// FNV-1a of the node's name: a node gets the same tuples wherever it stands in the catalog.
inline uint64_t name_seed(const std::string& name) {
    uint64_t h = 1469598103934665603ull;
    for (unsigned char c : name)
        h = (h ^ c) * 1099511628211ull;
    return h;
}

// kTuplesPerNode tuples of ordinary values only: each component, with equal odds, from
// kOrdinary or uniform in [-1, 1] (cosines, colours, unit-vector components).
inline std::vector<double> ordinary_tuples(const ProbeLayout& layout, uint64_t seed) {
    Lcg rng{seed};
    std::vector<double> tuples;
    for (size_t t = 0; t < kTuplesPerNode; ++t)
        for (const auto& field : layout.inputs)
            for (int c = 0; c < component_count(field.type); ++c)
                tuples.push_back(rng.next(2) ? rng.pick(kOrdinary)
                                             : rng.next(1u << 20) / double(1u << 19) - 1.0);
    return tuples;
}

// "(a,b,c)" of n values at `values`.
inline std::string components(const double* values, int n) {
    std::string s = "(";
    for (int c = 0; c < n; ++c) {
        char buf[32];
        std::snprintf(buf, sizeof buf, c ? ",%.9g" : "%.9g", values[c]);
        s += buf;
    }
    return s + ")";
}

// " a=(..) b=(..) -> gpu (..) cpu float (..)": tuple t's inputs and results; a strict-half run
// shows the CPU half result instead.
inline std::string describe_tuple(const ProbeRun& run, const std::vector<double>& in, size_t t) {
    std::string s;
    for (const auto& f : run.layout.inputs)
        s += " " + f.name + "=" +
             components(&in[t * run.layout.input_stride + f.offset], component_count(f.type));
    const int n = static_cast<int>(run.layout.output_stride);
    const std::vector<double>& cpu = run.strict_half ? run.cpu_half : run.cpu_float;
    return s + " -> gpu " + components(&run.gpu[t * n], n) +
           (run.strict_half ? " cpu half " : " cpu float ") + components(&cpu[t * n], n);
}

// Tuples whose GPU result has a NaN/Inf component where the CPU float result is finite, and
// the first of them; with `binary16_inputs`, only tuples whose inputs binary16 holds
// (|v| <= 65504: larger ones are infinite the moment they enter 16-bit arithmetic).
struct BrokenTuples {
    size_t count = 0, first = 0;
};
inline BrokenTuples gpu_breaks_where_float_holds(const ProbeRun& run, const std::vector<double>& in,
                                                 bool binary16_inputs) {
    BrokenTuples b;
    const size_t n = run.layout.output_stride, m = run.layout.input_stride;
    for (size_t t = 0; t < run.tuples; ++t) {
        bool representable = true;
        for (size_t k = 0; k < m && binary16_inputs; ++k)
            representable = representable && std::fabs(in[t * m + k]) <= 65504.0;
        bool broken = false;
        for (size_t k = 0; k < n; ++k)
            broken = broken || (!std::isfinite(run.gpu[t * n + k]) &&
                                std::isfinite(run.cpu_float[t * n + k]));
        if (representable && broken && b.count++ == 0) b.first = t;
    }
    return b;
}

} // namespace watergen::test
