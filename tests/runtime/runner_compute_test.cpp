// The numeric harness path: a compute shader over storage buffers (and textures).
#include "runner_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace watergen;

namespace {

const char* kSquare = R"(#version 450
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform Count { uint n; } count;
layout(set = 0, binding = 1) readonly buffer Inputs { float values[]; } inputs;
layout(set = 0, binding = 2) writeonly buffer Outputs { float values[]; } outputs;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < count.n) outputs.values[i] = inputs.values[i] * inputs.values[i];
}
)";

template <typename T> std::vector<uint8_t> as_bytes(const std::vector<T>& v) {
    std::vector<uint8_t> out(v.size() * sizeof(T));
    std::memcpy(out.data(), v.data(), out.size());
    return out;
}

} // namespace

TEST_CASE("compute shader squares N floats exactly", "[render][compute]") {
    VulkanRunner& runner = test::shared_runner();
    test::CompiledStage cs = test::compile_glsl(ShaderStage::Compute, kSquare);

    // 1000 is not a multiple of the 64-wide group: the tail group exercises the bounds
    // check, and the last 24 invocations must not write.
    const uint32_t n = 1000;
    std::vector<float> in(n);
    for (uint32_t i = 0; i < n; ++i)
        in[i] = (static_cast<float>(i) - 500.0f) * 0.37f + 0.001f;
    const uint32_t count = n;

    ComputeJob job;
    job.spirv = cs.spirv;
    job.reflection = cs.reflection;
    job.uniforms.resize(sizeof(count));
    std::memcpy(job.uniforms.data(), &count, sizeof(count));
    job.buffers["Inputs"] = as_bytes(in);
    job.output_sizes["Outputs"] = uint64_t{n} * sizeof(float);
    job.group_count_x = (n + 63) / 64;

    ComputeResult result = runner.run_compute(job);
    INFO(result.error);
    REQUIRE(result.ok);
    REQUIRE(result.buffers.count("Outputs") == 1);
    REQUIRE(result.buffers.at("Outputs").size() == n * sizeof(float));
    CHECK(result.buffers.at("Inputs") == job.buffers.at("Inputs")); // readonly: unchanged

    std::vector<float> out(n);
    std::memcpy(out.data(), result.buffers.at("Outputs").data(), n * sizeof(float));
    // Tolerance 0: Vulkan requires OpFMul to be correctly rounded, and so is the CPU's
    // float multiply; all inputs and squares are normal numbers, so denormal flushing
    // cannot differ either.
    size_t mismatches = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const float expected = in[i] * in[i];
        if (out[i] != expected && mismatches++ < 5)
            UNSCOPED_INFO("i=" << i << " got " << out[i] << " expected " << expected);
    }
    CHECK(mismatches == 0);
    CHECK(result.pipeline_ms > 0);
    CHECK(result.dispatch_ms > 0);
    CHECK(runner.validation_messages().empty());
    INFO(test::joined(runner.validation_messages()));
}

TEST_CASE("compute job without its input buffer names the binding", "[render][compute]") {
    VulkanRunner& runner = test::shared_runner();
    test::CompiledStage cs = test::compile_glsl(ShaderStage::Compute, kSquare);
    ComputeJob job;
    job.spirv = cs.spirv;
    job.reflection = cs.reflection;
    job.uniforms.resize(4);
    job.output_sizes["Outputs"] = 64;
    ComputeResult result = runner.run_compute(job);
    CHECK_FALSE(result.ok);
    CHECK(result.error.find("'Inputs'") != std::string::npos);
    INFO(result.error);
    CHECK(runner.validation_messages().empty());
}

namespace {

// Samples ramp (a 2x1 RGBA32F texture) at u = probe_in[i], v = 0.5, level 0.
const char* kSampleRamp = R"(#version 450
layout(local_size_x = 64) in;
layout(set = 0, binding = 1) uniform sampler linear_clamp;
layout(set = 0, binding = 2) uniform texture2D ramp;
layout(set = 0, binding = 8) readonly buffer Inputs { float u[]; } inputs;
layout(set = 0, binding = 9) writeonly buffer Outputs { float r[]; } outputs;
void main() {
    uint i = gl_GlobalInvocationID.x;
    outputs.r[i] = textureLod(sampler2D(ramp, linear_clamp), vec2(inputs.u[i], 0.5), 0.0).r;
}
)";

} // namespace

TEST_CASE("compute shader samples a job texture with float filter weights", "[render][compute]") {
    // Texels 0 and 1000 at u = 0.25 and 0.75: between them the linear filter returns
    // 1000 (2u - 0.5), outside it clamps. lavapipe computes the weight in float: measured
    // max error 3.0e-5 = 1000 x 2^-25, half an ulp of a weight near 1 (an 8-bit sub-texel
    // weight, as some GPUs use, would be up to 1000 / 512 = 2 off; 16 bits, 7.6e-3).
    VulkanRunner& runner = test::shared_runner();
    test::CompiledStage cs = test::compile_glsl(ShaderStage::Compute, kSampleRamp);
    const uint32_t n = 1024;
    std::vector<float> u(n);
    for (uint32_t i = 0; i < n; ++i)
        u[i] = static_cast<float>(i) / (n - 1);
    for (TextureFilter filter : {TextureFilter::Linear, TextureFilter::Nearest}) {
        ComputeJob job;
        job.spirv = cs.spirv;
        job.reflection = cs.reflection;
        job.textures["ramp"] = TextureData{2, 1, 1, {0, 0, 0, 1, 1000, 0, 0, 1}};
        job.filter = filter;
        job.buffers["Inputs"] = as_bytes(u);
        job.output_sizes["Outputs"] = uint64_t{n} * sizeof(float);
        job.group_count_x = n / 64;
        ComputeResult result = runner.run_compute(job);
        INFO(result.error);
        REQUIRE(result.ok);
        std::vector<float> r(n);
        std::memcpy(r.data(), result.buffers.at("Outputs").data(), n * sizeof(float));
        double max_error = 0;
        for (uint32_t i = 0; i < n; ++i) {
            const double x = double(u[i]) * 2.0 - 0.5; // texel space, texel centres at 0 and 1
            const double expected = filter == TextureFilter::Linear
                                        ? 1000.0 * std::clamp(x, 0.0, 1.0)
                                        : (u[i] < 0.5f ? 0.0 : 1000.0);
            max_error = std::max(max_error, std::fabs(r[i] - expected));
        }
        CHECK(max_error <= (filter == TextureFilter::Linear ? 6.1e-5 : 0.0));
        CHECK(runner.validation_messages().empty());
        INFO(test::joined(runner.validation_messages()));
    }
    ComputeJob missing;
    missing.spirv = cs.spirv;
    missing.reflection = cs.reflection;
    missing.buffers["Inputs"] = as_bytes(u);
    missing.output_sizes["Outputs"] = uint64_t{n} * sizeof(float);
    const ComputeResult failed = runner.run_compute(missing);
    CHECK_FALSE(failed.ok);
    CHECK(failed.error.find("texture sampled_image 'ramp' (set 0, binding 2) is not supplied") !=
          std::string::npos);
    INFO(failed.error);
}
