#include "runner_support.h"

#include "watergen/toolchain/glslang_stage.h"
#include "watergen/toolchain/reflection_stage.h"

#include <catch2/catch.hpp>

#include <cstring>
#include <memory>

namespace watergen::test {

VulkanRunner& shared_runner() {
    static std::unique_ptr<VulkanRunner> runner;
    static std::string error;
    if (!runner && error.empty()) {
        runner = VulkanRunner::create(DeviceOptions{}, &error);
        if (!runner && error.empty()) error = "(no message)";
    }
    INFO("VulkanRunner::create: " << error);
    REQUIRE(runner);
    return *runner;
}

namespace {
// Local formatting keeps the test independent of where format_diagnostic() is linked from.
std::string describe(const Diagnostic& d) {
    const char* severity = d.severity == Severity::Error     ? "error"
                           : d.severity == Severity::Warning ? "warning"
                                                             : "note";
    return d.file + ":" + std::to_string(d.line) + ": " + severity + ": " + d.message;
}
} // namespace

CompiledStage compile_glsl(ShaderStage stage, const std::string& source) {
    CompileRequest request;
    request.language = SourceLanguage::Glsl;
    request.stage = stage;
    request.source = source;
    request.file_name = std::string("test.") + to_string(stage);
    SpirvResult compiled = compile_to_spirv(request);
    for (const Diagnostic& d : compiled.diagnostics)
        UNSCOPED_INFO(describe(d));
    REQUIRE(compiled.ok());
    REQUIRE(compiled.diagnostics.empty());

    ReflectResult reflected = reflect_spirv(compiled.spirv, stage, request.file_name);
    for (const Diagnostic& d : reflected.diagnostics)
        UNSCOPED_INFO(describe(d));
    REQUIRE(reflected.diagnostics.empty());
    return {std::move(compiled.spirv), std::move(reflected.reflection)};
}

const CompiledStage& fullscreen_vertex() {
    // Vertices (-1,-1), (3,-1), (-1,3): one triangle covering the whole viewport.
    static const CompiledStage stage = compile_glsl(ShaderStage::Vertex, R"(#version 450
void main() {
    vec2 p = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)");
    return stage;
}

RenderJob fullscreen_job(const std::string& fragment, uint32_t width, uint32_t height) {
    const CompiledStage& vs = fullscreen_vertex();
    CompiledStage fs = compile_glsl(ShaderStage::Fragment, fragment);
    RenderJob job;
    job.vertex_spirv = vs.spirv;
    job.vertex_reflection = vs.reflection;
    job.fragment_spirv = std::move(fs.spirv);
    job.fragment_reflection = std::move(fs.reflection);
    job.width = width;
    job.height = height;
    return job;
}

namespace {
const DescriptorBinding& find_block(const Reflection& r, const std::string& block) {
    const DescriptorBinding* found = nullptr;
    for (const DescriptorBinding& b : r.bindings)
        if (b.name == block) found = &b;
    INFO("binding " << block);
    REQUIRE(found);
    return *found;
}
} // namespace

std::vector<uint8_t> block_bytes(const Reflection& r, const std::string& block) {
    return std::vector<uint8_t>(find_block(r, block).block_size, 0);
}

void put(std::vector<uint8_t>& bytes, const Reflection& r, const std::string& block,
         const std::string& member, const std::vector<float>& values) {
    for (const UniformMember& m : find_block(r, block).members) {
        if (m.name != member) continue;
        REQUIRE(values.size() * sizeof(float) <= m.size);
        REQUIRE(m.offset + m.size <= bytes.size());
        std::memcpy(bytes.data() + m.offset, values.data(), values.size() * sizeof(float));
        return;
    }
    FAIL("block " << block << " has no member " << member);
}

std::string joined(const std::vector<std::string>& lines) {
    std::string out;
    for (const auto& l : lines)
        out += l + "\n";
    return out;
}

} // namespace watergen::test
