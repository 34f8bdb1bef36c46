// Does lavapipe's float16_t arithmetic round every operation to binary16 (watergen issue 14)?
// A compute shader with GL_EXT_shader_explicit_arithmetic_types_float16 runs known cases in
// float16_t and in float; each result is compared with two CPU binary16 references (the
// evaluator's round_to_half and GCC's _Float16) and with the float32 result rounded once at
// the end. Cases are chosen so that per-operation rounding and "32 bits, converted at the
// end" give different answers wherever they can.
#include "shared_runner.h"

#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/toolchain/glslang_stage.h"
#include "watergen/toolchain/reflection_stage.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace watergen;

namespace {

// The shader's op codes, in its switch order.
enum class Op : uint32_t {
    Add,               // a + b
    Mul,               // a * b
    Div,               // a / b
    AddThenSub,        // (a + b) - a: is the sum rounded before the subtraction?
    MulThenDiv,        // (a * b) / c: does an overflowed product stay infinite?
    MulThenMul,        // (a * b) * c: is an underflowed product rounded to a subnormal?
    MulAdd,            // a * b + c as written: may the compiler fuse it?
    PreciseMulAdd,     // the same with `precise`: two roundings required
    Fma,               // fma(a, b, c): one rounding
    Sqrt,              // sqrt(a)
    Exp,               // exp(a)
    Log,               // log(a)
    Pow,               // pow(a, b)
    Sin,               // sin(a)
    Convert,           // float16_t(a) from a float32 input that needs rounding
    ConvertThenAdd,    // float16_t(a) + float16_t(b) from float32 inputs
    PreciseAddThenSub, // (a + b) - a with `precise`: no algebraic shortcut allowed
};

// The GLSL bodies of both evaluations come from one macro, so they cannot drift apart.
const char* kShader = R"(#version 450
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require
#extension GL_EXT_shader_16bit_storage : require
layout(local_size_x = 32) in;
layout(set = 0, binding = 0) readonly buffer Ops { uint op[]; } ops;
layout(set = 0, binding = 1) readonly buffer Halves { float16_t v[]; } halves;
layout(set = 0, binding = 2) readonly buffer Floats { float v[]; } floats;
layout(set = 0, binding = 3) writeonly buffer Results16 { float16_t v[]; } results16;
layout(set = 0, binding = 4) writeonly buffer Results32 { float v[]; } results32;
#define DEFINE_RUN(T, NAME) \
T NAME(uint op, T a, T b, T c, float a32, float b32) { \
    switch (op) { \
    case 0u: return a + b; \
    case 1u: return a * b; \
    case 2u: return a / b; \
    case 3u: { T s = a + b; return s - a; } \
    case 4u: { T p = a * b; return p / c; } \
    case 5u: { T p = a * b; return p * c; } \
    case 6u: return a * b + c; \
    case 7u: { precise T p = a * b; precise T s = p + c; return s; } \
    case 8u: return fma(a, b, c); \
    case 9u: return sqrt(a); \
    case 10u: return exp(a); \
    case 11u: return log(a); \
    case 12u: return pow(a, b); \
    case 13u: return sin(a); \
    case 14u: return T(a32); \
    case 15u: return T(a32) + T(b32); \
    case 16u: { precise T s = a + b; precise T r = s - a; return r; } \
    } \
    return T(0); \
}
DEFINE_RUN(float16_t, run_half)
DEFINE_RUN(float, run_float)
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= ops.op.length()) return;
    float a32 = floats.v[3 * i], b32 = floats.v[3 * i + 1], c32 = floats.v[3 * i + 2];
    results16.v[i] = run_half(ops.op[i], halves.v[3 * i], halves.v[3 * i + 1],
                              halves.v[3 * i + 2], a32, b32);
    results32.v[i] = run_float(ops.op[i], a32, b32, c32, a32, b32);
}
)";

struct Case {
    const char* name;
    Op op;
    double a, b, c; // binary16 values, except the float32 inputs of the Convert ops
};

const double kTiny = std::ldexp(1.0, -24); // smallest binary16 subnormal
const double kOnePlus = 1.0 + 0x1p-10;     // 1 + one binary16 ulp
const double kProduct = 1.0 + 0x1p-9;      // kOnePlus^2 rounded to binary16
const double kFloat07 = double(0.7f);      // 0.69999998807907104
const double kFloat01 = double(0.1f);
const double kSubnormal = 1023.0 * kTiny; // 6.0975551605e-05, largest subnormal

const std::vector<Case>& cases() {
    static const std::vector<Case> all = {
        {"2049 + 1 (inputs converted)", Op::ConvertThenAdd, 2049, 1, 0},
        {"2048 + 1 (tie to even)", Op::Add, 2048, 1, 0},
        {"2048 + 3 (tie to even, up)", Op::Add, 2048, 3, 0},
        {"(2048 + 1) - 2048", Op::AddThenSub, 2048, 1, 0},
        {"precise (2048 + 1) - 2048", Op::PreciseAddThenSub, 2048, 1, 0},
        {"65504 * 2", Op::Mul, 65504, 2, 0},
        {"(65504 * 2) / 4", Op::MulThenDiv, 65504, 2, 4},
        {"1 / 3", Op::Div, 1, 3, 0},
        {"2^-24 * 0.5", Op::Mul, kTiny, 0.5, 0},
        {"(2^-24 * 0.5) * 4", Op::MulThenMul, kTiny, 0.5, 4},
        {"1023*2^-24 * 0.5", Op::Mul, kSubnormal, 0.5, 0},
        {"2^-14 * 0.5 (normal->subnormal)", Op::Mul, 0x1p-14, 0.5, 0},
        {"1 + 2^-11 (tie to even)", Op::Add, 1, 0x1p-11, 0},
        {"(1 + 2^-11) - 1", Op::AddThenSub, 1, 0x1p-11, 0},
        {"precise (1 + 2^-11) - 1", Op::PreciseAddThenSub, 1, 0x1p-11, 0},
        {"1 + 3*2^-11", Op::Add, 1, 3 * 0x1p-11, 0},
        {"a*b+c, a=b=1+2^-10", Op::MulAdd, kOnePlus, kOnePlus, -kProduct},
        {"precise a*b+c", Op::PreciseMulAdd, kOnePlus, kOnePlus, -kProduct},
        {"fma(a,b,c)", Op::Fma, kOnePlus, kOnePlus, -kProduct},
        {"sqrt(2)", Op::Sqrt, 2, 0, 0},
        {"exp(1)", Op::Exp, 1, 0, 0},
        {"exp(0.5)", Op::Exp, 0.5, 0, 0},
        {"exp(-8)", Op::Exp, -8, 0, 0},
        {"log(2)", Op::Log, 2, 0, 0},
        {"log(10)", Op::Log, 10, 0, 0},
        {"log(1000)", Op::Log, 1000, 0, 0},
        {"pow(2, 0.5)", Op::Pow, 2, 0.5, 0},
        {"pow(10, 2.5)", Op::Pow, 10, 2.5, 0},
        {"sin(1)", Op::Sin, 1, 0, 0},
        {"sin(3)", Op::Sin, 3, 0, 0},
        {"sin(100)", Op::Sin, 100, 0, 0},
        {"half(0.7f) (RTE vs RTZ)", Op::Convert, kFloat07, 0, 0},
        {"half(0.1f)", Op::Convert, kFloat01, 0, 0},
        {"half(65520.0f) (inf vs 65504)", Op::Convert, 65520, 0, 0},
        {"half(1.5*2^-24) (subnormal tie)", Op::Convert, 1.5 * kTiny, 0, 0},
    };
    return all;
}

// Evaluates a case in T, with `round` applied to every input and every operation's result;
// the operations themselves run in T (or in double for the library functions), so the only
// rounding to the target format is `round`'s.
template <typename T, typename Round> double evaluate(const Case& k, Round round) {
    const T a = round(k.a), b = round(k.b), c = round(k.c);
    const auto d = [](T v) { return static_cast<double>(v); };
    switch (k.op) {
    case Op::Add:
    case Op::ConvertThenAdd:
        return d(round(d(a) + d(b)));
    case Op::Mul:
        return d(round(d(a) * d(b)));
    case Op::Div:
        return d(round(d(a) / d(b)));
    case Op::AddThenSub:
    case Op::PreciseAddThenSub:
        return d(round(d(round(d(a) + d(b))) - d(a)));
    case Op::MulThenDiv:
        return d(round(d(round(d(a) * d(b))) / d(c)));
    case Op::MulThenMul:
        return d(round(d(round(d(a) * d(b))) * d(c)));
    case Op::MulAdd:
    case Op::PreciseMulAdd:
        return d(round(d(round(d(a) * d(b))) + d(c)));
    case Op::Fma:
        return d(round(std::fma(d(a), d(b), d(c))));
    case Op::Sqrt:
        return d(round(std::sqrt(d(a))));
    case Op::Exp:
        return d(round(std::exp(d(a))));
    case Op::Log:
        return d(round(std::log(d(a))));
    case Op::Pow:
        return d(round(std::pow(d(a), d(b))));
    case Op::Sin:
        return d(round(std::sin(d(a))));
    case Op::Convert:
        return d(a);
    }
    return std::nan("");
}

// binary16 by the CPU evaluator's rounding (double arithmetic, round_to_half per operation).
double evaluator_binary16(const Case& k) {
    return evaluate<double>(k, [](double v) { return round_to_half(v); });
}

// binary16 by GCC's _Float16 (libgcc's conversion; float arithmetic on x86-64 without
// AVX512-FP16, rounded back by each cast), an implementation independent of round_to_half.
double gcc_binary16(const Case& k) {
    return evaluate<_Float16>(k, [](double v) { return static_cast<_Float16>(v); });
}

// The float32 evaluation: what a driver that ignores float16_t would compute.
double float32_value(const Case& k) {
    return evaluate<float>(k, [](double v) { return static_cast<float>(v); });
}

// What lavapipe (Mesa 22.3) computes, as measured: every operation rounded to binary16, after
// NIR's rewrites at the shader's bit size. (a + b) - a folds to b unless `precise`; fma is
// split into a rounded multiply and a rounded add; exp(x) = exp2(x * log2(e)),
// log(x) = log2(x) * ln(2) and pow(a, b) = exp2(b * log2(a)), each step rounded to binary16
// (so exp and log can miss the correctly rounded result by an ulp or two).
double lavapipe_binary16(const Case& k) {
    const auto h = [](double v) { return round_to_half(v); };
    switch (k.op) {
    case Op::AddThenSub:
        return h(k.b);
    case Op::Fma: {
        Case split = k;
        split.op = Op::MulAdd;
        return evaluator_binary16(split);
    }
    case Op::Exp:
        return h(std::exp2(h(k.a * h(M_LOG2E))));
    case Op::Log:
        return h(h(std::log2(k.a)) * h(M_LN2));
    case Op::Pow:
        return h(std::exp2(h(k.b * h(std::log2(k.a)))));
    default:
        return evaluator_binary16(k);
    }
}

bool is_library_function(Op op) {
    return op == Op::Exp || op == Op::Log || op == Op::Pow || op == Op::Sin || op == Op::Sqrt;
}

// Distance in binary16 ulps (at the larger magnitude's binade; subnormals share 2^-24).
double half_ulps(double x, double y) {
    int e = 0;
    std::frexp(std::max(std::fabs(x), std::fabs(y)), &e);
    return std::fabs(x - y) / std::ldexp(1.0, std::max(e - 1, -14) - 10);
}

uint16_t half_bits(double v) {
    const _Float16 h = static_cast<_Float16>(v);
    uint16_t bits = 0;
    std::memcpy(&bits, &h, sizeof(bits));
    return bits;
}

double from_half_bits(const uint8_t* p) {
    _Float16 h;
    std::memcpy(&h, p, sizeof(h));
    return static_cast<double>(h);
}

template <typename T> void append(std::vector<uint8_t>& out, T value) {
    const auto* p = reinterpret_cast<const uint8_t*>(&value);
    out.insert(out.end(), p, p + sizeof(T));
}

struct Measured {
    double half = 0;    // the float16_t evaluation on the device
    double float32 = 0; // the float evaluation on the device
};

std::vector<Measured> run_on_device(VulkanRunner& runner) {
    CompileRequest request;
    request.stage = ShaderStage::Compute;
    request.source = kShader;
    request.file_name = "float16_probe.comp";
    SpirvResult compiled = compile_to_spirv(request);
    for (const Diagnostic& d : compiled.diagnostics)
        UNSCOPED_INFO(format_diagnostic(d));
    REQUIRE(compiled.ok());
    ReflectResult reflected = reflect_spirv(compiled.spirv, ShaderStage::Compute, "probe");
    REQUIRE(reflected.diagnostics.empty());

    const std::vector<Case>& all = cases();
    const size_t n = all.size();
    ComputeJob job;
    job.spirv = compiled.spirv;
    job.reflection = reflected.reflection;
    for (const Case& k : all) {
        append(job.buffers["Ops"], static_cast<uint32_t>(k.op));
        for (double v : {k.a, k.b, k.c}) {
            append(job.buffers["Halves"], half_bits(v));
            append(job.buffers["Floats"], static_cast<float>(v));
        }
    }
    job.output_sizes["Results16"] = (n + n % 2) * sizeof(uint16_t); // whole 32-bit words
    job.output_sizes["Results32"] = n * sizeof(float);
    job.group_count_x = static_cast<uint32_t>((n + 31) / 32);
    ComputeResult result = runner.run_compute(job);
    INFO(result.error);
    REQUIRE(result.ok);

    std::vector<Measured> out(n);
    const std::vector<uint8_t>& r16 = result.buffers.at("Results16");
    const std::vector<uint8_t>& r32 = result.buffers.at("Results32");
    for (size_t i = 0; i < n; ++i) {
        float f = 0;
        std::memcpy(&f, r32.data() + 4 * i, sizeof(f));
        out[i] = {from_half_bits(r16.data() + 2 * i), static_cast<double>(f)};
    }
    return out;
}

// Same value, with -0 != +0 (a sign error is an error) and NaN == NaN.
bool same(double x, double y) {
    if (std::isnan(x) || std::isnan(y)) return std::isnan(x) && std::isnan(y);
    return x == y && std::signbit(x) == std::signbit(y);
}

const char* verdict(double device, double binary16, double model, double rounded_once) {
    if (same(device, binary16) && same(device, rounded_once)) return "both agree";
    if (same(device, binary16)) return "binary16 per op";
    if (same(device, model)) return "binary16 per op, op rewritten";
    if (same(device, rounded_once)) return "float32, rounded at the end";
    return "neither";
}

} // namespace

TEST_CASE("lavapipe rounds every float16_t operation to binary16", "[render][float16]") {
    VulkanRunner& runner = test::shared_runner();
    const DeviceInfo& info = runner.device_info();
    if (!info.shader_float16 || !info.storage_buffer_16bit) {
        WARN(info.name << " has no shaderFloat16 / storageBuffer16BitAccess: probe skipped");
        return;
    }
    const std::vector<Measured> measured = run_on_device(runner);
    for (const std::string& m : runner.validation_messages())
        UNSCOPED_INFO(m);
    CHECK(runner.validation_messages().empty());

    std::printf("%-34s %-16s %-16s %-16s %-16s %s\n", "case", "binary16", "lavapipe f16",
                "lavapipe f32", "f32 rounded", "verdict");
    for (size_t i = 0; i < cases().size(); ++i) {
        const Case& k = cases()[i];
        const Measured& m = measured[i];
        const double expected = evaluator_binary16(k);
        const double model = lavapipe_binary16(k);
        const double rounded_once = round_to_half(m.float32);
        std::printf("%-34s %-16.10g %-16.10g %-16.10g %-16.10g %s\n", k.name, expected, m.half,
                    m.float32, rounded_once, verdict(m.half, expected, model, rounded_once));
        INFO(k.name << ": binary16 " << expected << ", model " << model << ", device " << m.half
                    << ", device float " << m.float32);
        // The two CPU references agree, and the device's float path is float32.
        CHECK(same(expected, gcc_binary16(k)));
        if (is_library_function(k.op))
            CHECK(std::fabs(m.float32 - float32_value(k)) <= 4e-7 * std::fabs(float32_value(k)));
        else
            CHECK(same(m.float32, float32_value(k)));
        // The device's float16_t result is binary16 after every (possibly rewritten) op,
        // within two ulps of the correctly rounded one where a library function is lowered.
        CHECK(same(m.half, model));
        if (is_library_function(k.op)) CHECK(half_ulps(m.half, expected) <= 2.0);
    }
}
