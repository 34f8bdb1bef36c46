#include "watergen/toolchain/tool_process_chain.h"

#include "watergen/toolchain/child_process.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace watergen {

namespace fs = std::filesystem;

ProcessChainResult run_tool_process_chain(const CompileRequest& request,
                                          const std::string& work_dir) {
    ProcessChainResult result;
    const fs::path dir(work_dir);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) {
        result.error = "cannot create " + work_dir + ": " + ec.message();
        return result;
    }
    const bool hlsl = request.language == SourceLanguage::Hlsl;
    const std::string stage = stage_tag(request.stage);
    auto path = [&](const char* name) { return (dir / name).string(); };
    const std::string src = path(hlsl ? "shader.hlsl" : "shader.glsl");
    {
        std::ofstream out(src, std::ios::binary);
        out << request.source;
        if (!out) {
            result.error = "cannot write " + src;
            return result;
        }
    }

    std::vector<std::string> compile = {"glslangValidator", "-V", "--target-env",
                                        "vulkan1.1",        "-S", stage};
    if (hlsl) compile.insert(compile.end(), {"-D", "-e", request.entry_point});
    compile.insert(compile.end(), {"-o", path("shader.spv"), src});

    const std::vector<std::vector<std::string>> steps = {
        compile,
        {"spirv-val", "--target-env", "vulkan1.1", path("shader.spv")},
        {"spirv-opt", "-O", "--skip-validation", path("shader.spv"), "-o", path("shader.opt.spv")},
        {"spirv-val", "--target-env", "vulkan1.1", path("shader.opt.spv")},
        {"spirv-cross", path("shader.opt.spv"), "--version", "330", "--no-es",
         "--no-420pack-extension", "--output", path("shader.330.glsl")},
        {"spirv-cross", path("shader.opt.spv"), "--es", "--version", "300", "--output",
         path("shader.300es.glsl")},
        {"spirv-cross", path("shader.opt.spv"), "--msl", "--output", path("shader.metal")},
        {"glslangValidator", "-S", stage, path("shader.330.glsl")},
        {"glslangValidator", "-S", stage, path("shader.300es.glsl")},
        {"spirv-cross", path("shader.spv"), "--reflect", "--output", path("shader.json")},
    };
    for (const auto& step : steps) {
        result.error = run_child_process(step, dir);
        if (!result.error.empty()) return result;
    }
    result.ok = true;
    return result;
}

} // namespace watergen
