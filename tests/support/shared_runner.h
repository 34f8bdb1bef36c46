// One Vulkan runner (lavapipe, validation on) per test binary.
#pragma once

#include <catch2/catch.hpp>

#include <string>

#include "watergen/eval/probe/probe.h"
#include "watergen/runner/vulkan_runner.h"

namespace watergen::test {

inline VulkanRunner& shared_runner() {
    static std::unique_ptr<VulkanRunner> r = [] {
        std::string error;
        auto created = VulkanRunner::create({}, &error);
        if (!created) FAIL("no Vulkan device: " << error);
        return created;
    }();
    return *r;
}

// run_probe on the shared runner, failing the test on diagnostics, errors or validation messages.
inline ProbeRun checked_probe(const Graph& g, Language lang, const std::vector<double>& inputs,
                              const std::map<std::string, std::vector<double>>& uniforms = {},
                              const std::map<std::string, TextureData>& textures = {},
                              const EmitOptions& options = {}) {
    ProbeRun run = run_probe(shared_runner(), g, lang, inputs, uniforms, textures, options);
    std::string diagnostics;
    for (const auto& d : run.diagnostics)
        diagnostics += format_diagnostic(d) + "\n";
    INFO(diagnostics << run.error);
    REQUIRE(run.ok());
    CHECK(run.validation_messages.empty());
    return run;
}

} // namespace watergen::test
