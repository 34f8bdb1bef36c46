#include "watergen/ir/cpu/cpu_evaluator.h"

#include "block_evaluator.h"
#include "block_program.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

namespace watergen {

const char* to_string(EvalPrecision p) {
    switch (p) {
    case EvalPrecision::Double:
        return "double";
    case EvalPrecision::Float:
        return "float";
    case EvalPrecision::Half:
        return "half";
    }
    return "?";
}

double round_to_half(double v) {
    if (!std::isfinite(v) || v == 0.0) return v;
    const double a = std::fabs(v);
    // 65504 is the largest half; values from the midpoint to 65536 upwards round to infinity.
    if (a >= 65520.0) return std::copysign(std::numeric_limits<double>::infinity(), v);
    int e = 0;
    std::frexp(a, &e);                         // a in [2^(e-1), 2^e)
    const int exponent = std::max(e - 1, -14); // below 2^-14 the spacing stays 2^-24
    const double ulp = std::ldexp(1.0, exponent - 10);
    return std::copysign(std::nearbyint(a / ulp) * ulp, v);
}

namespace {

// Position of a binary16 value on the number line in ulps: the count of binary16 values between
// +0 and it (negative below zero), infinity one past 65504.
int64_t half_ordinal(double v) {
    const double a = std::fabs(round_to_half(v));
    int64_t n = 0;
    if (std::isinf(a)) {
        n = 31 * 1024; // exponents 0..30 hold 1024 values each
    } else if (a < 0x1p-14) {
        n = static_cast<int64_t>(a / 0x1p-24); // subnormals: spacing 2^-24
    } else {
        int e = 0;
        const double m = std::frexp(a, &e); // a = m 2^e, m in [0.5, 1)
        n = int64_t(e + 14) * 1024 + static_cast<int64_t>((m * 2 - 1) * 1024);
    }
    return std::signbit(v) ? -n : n;
}

} // namespace

int64_t half_ulp_distance(double a, double b) {
    if (std::isnan(a) || std::isnan(b)) return -1;
    const int64_t d = half_ordinal(a) - half_ordinal(b);
    return d < 0 ? -d : d;
}

void HalfAgreement::add(double test, double reference, size_t index) {
    if (!std::isfinite(test) || !std::isfinite(reference)) return;
    const int64_t d = half_ulp_distance(test, reference);
    ++values;
    equal += d == 0;
    within_1 += d <= 1;
    if (d > max_ulps) {
        max_ulps = d;
        max_index = index;
    }
}

double round_to_half_toward_zero(double v) {
    const double r = round_to_half(v);
    if (!std::isfinite(v) || std::fabs(r) <= std::fabs(v)) return r;
    if (std::isinf(r)) return std::copysign(65504.0, v);
    // Rounded away from zero: one binary16 step back. Below a power of two the spacing is
    // half the one above it.
    const double a = std::fabs(r);
    int e = 0;
    const double m = std::frexp(a, &e); // a = m 2^e, m in [0.5, 1)
    const int exponent = std::max(e - 1 - (m == 0.5 ? 1 : 0), -14);
    return std::copysign(a - std::ldexp(1.0, exponent - 10), v);
}

double round_to(double v, EvalPrecision p) {
    switch (p) {
    case EvalPrecision::Double:
        return v;
    case EvalPrecision::Float:
        return static_cast<double>(static_cast<float>(v));
    case EvalPrecision::Half:
        return round_to_half(static_cast<double>(static_cast<float>(v)));
    }
    return v;
}

namespace {

std::optional<uint32_t> find_output(const Graph& g, const std::string& name) {
    for (const auto& o : g.outputs())
        if (o.name == name) return o.node;
    return std::nullopt;
}

} // namespace

EvalResult evaluate(const Graph& g, const std::string& output, const EvalInputs& inputs,
                    EvalPrecision precision) {
    EvalResult result;
    const auto root = find_output(g, output);
    if (!root) {
        result.error = "graph has no output '" + output + "'";
        return result;
    }
    if (has_errors(g.diagnostics())) {
        result.error = "graph has type errors";
        return result;
    }
    result.components = component_count(g.node(*root).type);
    result.values.resize(inputs.lanes * static_cast<size_t>(result.components));
    const Program program = compile_program(g, *root, inputs, precision);
    // The first block that cannot be evaluated fails the evaluation, before any is.
    const size_t blocks = (inputs.lanes + kBlock - 1) / kBlock;
    for (size_t b = 0; b < blocks && !program.checks.empty(); ++b) {
        const size_t begin = b * kBlock;
        result.error = block_error(program, begin, std::min(kBlock, inputs.lanes - begin));
        if (!result.error.empty()) return result;
    }
    // Blocks are shared out to the threads in turn; each thread has its own evaluator, and a
    // lane's value does not depend on which thread computes it.
    const size_t wanted = inputs.threads ? inputs.threads : std::thread::hardware_concurrency();
    const size_t threads = std::max<size_t>(1, std::min<size_t>(wanted, blocks));
    auto work = [&](size_t first) {
        if (first >= blocks) return;
        BlockEvaluator block(program, inputs);
        const size_t comps = static_cast<size_t>(result.components);
        for (size_t b = first; b < blocks; b += threads) {
            const size_t begin = b * kBlock, count = std::min(kBlock, inputs.lanes - begin);
            block.run(begin, count);
            block.read_root(count, result.values.data() + begin * comps);
        }
    };
    std::vector<std::thread> pool;
    for (size_t t = 1; t < threads; ++t)
        pool.emplace_back(work, t);
    work(0);
    for (auto& t : pool)
        t.join();
    return result;
}

std::vector<EvalSite> evaluation_sites(const Graph& g, const std::string& output,
                                       const EvalInputs& inputs) {
    const auto root = find_output(g, output);
    if (!root || has_errors(g.diagnostics())) return {};
    return compile_program(g, *root, inputs, EvalPrecision::Double).sites;
}

EvalResult evaluate_image(const Graph& g, const std::string& output, EvalInputs inputs,
                          uint32_t width, uint32_t height, EvalPrecision precision) {
    // Lanes in 2x2 quads so derivatives see their neighbours; odd edges are padded.
    const uint32_t qw = (width + 1) / 2, qh = (height + 1) / 2;
    inputs.lanes = static_cast<size_t>(qw) * qh * 4;
    std::vector<double> uv(inputs.lanes * 2);
    for (uint32_t qy = 0; qy < qh; ++qy)
        for (uint32_t qx = 0; qx < qw; ++qx)
            for (uint32_t i = 0; i < 4; ++i) {
                const size_t lane = (static_cast<size_t>(qy) * qw + qx) * 4 + i;
                uv[lane * 2 + 0] = (2.0 * qx + (i & 1) + 0.5) / width;
                uv[lane * 2 + 1] = (2.0 * qy + (i >> 1) + 0.5) / height;
            }
    inputs.varyings["v_uv"] = std::move(uv);
    EvalResult quads = evaluate(g, output, inputs, precision);
    if (!quads.ok()) return quads;
    EvalResult image;
    image.components = quads.components;
    image.values.resize(static_cast<size_t>(width) * height * quads.components);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const size_t lane =
                (static_cast<size_t>(y / 2) * qw + x / 2) * 4 + (x & 1) + 2 * (y & 1);
            for (int c = 0; c < quads.components; ++c)
                image.values[(static_cast<size_t>(y) * width + x) * quads.components + c] =
                    quads.values[lane * quads.components + c];
        }
    return image;
}

} // namespace watergen
