// Shared pieces of the render tests: one runner per test process (instance creation with
// the validation layer costs ~100 ms, and reuse is part of what is being tested), GLSL
// compiled in-process with the toolchain, and uniform block packing by reflection offset.
#pragma once

#include "watergen/runner/vulkan_runner.h"

#include <cstdint>
#include <string>
#include <vector>

namespace watergen::test {

// The process-wide lavapipe runner with validation on; REQUIREs that it exists.
VulkanRunner& shared_runner();

struct CompiledStage {
    std::vector<uint32_t> spirv;
    Reflection reflection;
};

// GLSL 450 -> SPIR-V + reflection; REQUIREs success with no diagnostics at all.
CompiledStage compile_glsl(ShaderStage stage, const std::string& source);

// Fullscreen triangle driven by gl_VertexIndex (no vertex buffers).
const CompiledStage& fullscreen_vertex();

// A RenderJob with the fullscreen vertex stage and `fragment` compiled.
RenderJob fullscreen_job(const std::string& fragment, uint32_t width, uint32_t height);

// Block bytes sized from reflection; `put` writes floats at a member's reflected offset.
std::vector<uint8_t> block_bytes(const Reflection& r, const std::string& block);
void put(std::vector<uint8_t>& bytes, const Reflection& r, const std::string& block,
         const std::string& member, const std::vector<float>& values);

// Formats validation messages for a failure report.
std::string joined(const std::vector<std::string>& lines);

} // namespace watergen::test
