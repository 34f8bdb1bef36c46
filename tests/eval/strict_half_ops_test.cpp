// Each IR operation in strict half (16-bit arithmetic) on lavapipe against the CPU evaluator's
// half mode. The GLSL path computes every built-in in binary16 steps, in the order the CPU model
// follows (dot left to right, normalize as x / length, mix as x (1 - a) + y a, exp as
// exp2(x log2 e), matrix columns last to first, ...): bit-exact but for atan2 (lavapipe's
// polynomial) and NIR's inexact rewrites ((a + b) - a -> b in smoothstep's edges). glslang 12's
// HLSL front end has no 16-bit intrinsics: they run at 32 bits and are rounded once, so the
// HLSL path is held against the exact result rounded once. Distances in binary16 steps; run
// this binary to print the table.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <functional>

#include "shared_runner.h"
#include "watergen/ir/core/dsl.h"
#include "watergen/ir/cpu/cpu_evaluator.h"

using namespace watergen;

namespace {

struct OpCase {
    const char* name;
    Type type;     // of every input
    int inputs;    // 1..3: a, b, c
    double lo, hi; // input range (uniform)
    std::function<Expr(Expr, Expr, Expr)> f;
    // Largest distance allowed, in binary16 steps: GLSL path from the CPU half model; HLSL path
    // from the exact result rounded once (-1: not checked; the case composes several operations
    // in 16-bit arithmetic before the one it names).
    int glsl_max = 0, hlsl_max = 1;
};

HalfAgreement agreement(const std::vector<double>& gpu, const std::vector<double>& cpu) {
    HalfAgreement a;
    for (size_t i = 0; i < gpu.size(); ++i)
        a.add(gpu[i], cpu[i], i);
    return a;
}

// Inputs already binary16 (so both sides start from the same values), from a 64-bit LCG.
std::vector<double> inputs(const OpCase& c, size_t tuples) {
    uint64_t state = 0x9e3779b97f4a7c15ull;
    std::vector<double> v;
    const int n = component_count(c.type) * c.inputs;
    for (size_t t = 0; t < tuples * n; ++t) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        const double u = double(state >> 11) / 9007199254740992.0;
        v.push_back(round_to_half(c.lo + (c.hi - c.lo) * u));
    }
    return v;
}

} // namespace

TEST_CASE("strict_half_operations_on_lavapipe_against_the_cpu_half_model", "[probe][half]") {
    using E = Expr;
    const std::vector<OpCase> cases = {
        {"add", Type::Float, 2, -100, 100, [](E a, E b, E) { return a + b; }},
        {"mul", Type::Float, 2, -100, 100, [](E a, E b, E) { return a * b; }},
        {"div", Type::Float, 2, 0.5, 100, [](E a, E b, E) { return a / b; }},
        {"sqrt", Type::Float, 1, 0, 1000, [](E a, E, E) { return sqrt(a); }},
        {"rsqrt", Type::Float, 1, 0.01, 1000, [](E a, E, E) { return rsqrt(a); }},
        {"exp", Type::Float, 1, -8, 8, [](E a, E, E) { return exp(a); }},
        {"exp2", Type::Float, 1, -12, 12, [](E a, E, E) { return exp2(a); }},
        {"log", Type::Float, 1, 0.01, 1000, [](E a, E, E) { return log(a); }},
        {"pow", Type::Float, 2, 0.01, 4, [](E a, E b, E) { return pow(a, b); }},
        {"sin", Type::Float, 1, -3.2, 3.2, [](E a, E, E) { return sin(a); }},
        {"cos", Type::Float, 1, -3.2, 3.2, [](E a, E, E) { return cos(a); }},
        // lavapipe's atan polynomial at 16 bits is not the correctly rounded atan.
        {"atan2", Type::Float, 2, -4, 4, [](E a, E b, E) { return atan2(a, b); }, 3},
        {"mix", Type::Float, 3, 0, 1, [](E a, E b, E c) { return mix(a, b, c); }},
        {"smoothstep", Type::Float, 1, -0.2, 1.2,
         [](E a, E, E) {
             return smoothstep(constant(a.graph(), 0.0), constant(a.graph(), 1.0), a);
         }},
        {"fract", Type::Float, 1, -50, 50, [](E a, E, E) { return fract(a); }},
        // wg_mod is 16-bit arithmetic in HLSL too: floor(x / y) of the rounded quotient.
        {"mod", Type::Float, 2, 0.5, 50, [](E a, E b, E) { return mod(a, b); }, 0, -1},
        {"dot3", Type::Vec3, 2, -4, 4, [](E a, E b, E) { return dot(a, b); }},
        {"length3", Type::Vec3, 1, -4, 4, [](E a, E, E) { return length(a); }},
        {"normalize3", Type::Vec3, 1, -4, 4, [](E a, E, E) { return normalize(a); }},
        {"cross", Type::Vec3, 2, -4, 4, [](E a, E b, E) { return cross(a, b); }},
        {"reflect", Type::Vec3, 2, -1, 1, [](E a, E b, E) { return reflect(a, normalize(b)); }, 0,
         -1},
        {"refract", Type::Vec3, 3, -1, 1,
         [](E a, E b, E c) { return refract(a, b, c.x() * 0.5 + 0.75); }, 0, -1},
        {"smoothstep_edges", Type::Float, 3, -2, 2,
         [](E a, E b, E c) { return smoothstep(a, a + abs(b) + 0.25, c); }, 6, -1},
        {"matmul", Type::Vec3, 3, -4, 4,
         [](E a, E b, E c) { return mat3(a, b, c) * normalize(a + b); }, 0, -1},
    };
    constexpr size_t kTuples = 4096;
    std::printf("%-16s %4s %8s %8s %9s %6s %8s %6s\n", "op", "lang", "values", "equal %",
                "<=1ulp %", "max", "once<=1", "max");
    for (const auto& c : cases) {
        Graph g;
        Expr in[3];
        const char* names[3] = {"a", "b", "c"};
        for (int i = 0; i < c.inputs; ++i)
            in[i] = varying(g, names[i], c.type);
        {
            RelaxedScope relaxed(g, true);
            g.set_output("r", c.f(in[0], in[1], in[2]).id());
        }
        const std::vector<double> tuples = inputs(c, kTuples);
        for (Language lang : {Language::Glsl, Language::Hlsl}) {
            INFO(c.name << " " << to_string(lang));
            const ProbeRun run = test::checked_probe(g, lang, tuples, {}, {}, EmitOptions{true});
            const HalfAgreement u = agreement(run.gpu, run.cpu_half);
            std::vector<double> once(run.cpu_double.size());
            for (size_t i = 0; i < once.size(); ++i)
                once[i] = round_to_half(run.cpu_double[i]);
            const HalfAgreement o = agreement(run.gpu, once);
            std::printf("%-16s %4s %8zu %8.2f %9.2f %6lld %8.2f %6lld\n", c.name, to_string(lang),
                        u.values, 100.0 * u.equal / u.values, 100.0 * u.within_1 / u.values,
                        static_cast<long long>(u.max_ulps), 100.0 * o.within_1 / o.values,
                        static_cast<long long>(o.max_ulps));
            if (lang == Language::Glsl) {
                CHECK(u.max_ulps <= c.glsl_max);
            } else if (c.hlsl_max >= 0) {
                CHECK(o.max_ulps <= c.hlsl_max);
            }
            CHECK(u.values == run.gpu.size()); // every result finite on both sides
        }
    }
}
