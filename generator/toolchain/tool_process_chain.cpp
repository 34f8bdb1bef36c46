#include "watergen/toolchain/tool_process_chain.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

extern char** environ;

namespace watergen {
namespace {

namespace fs = std::filesystem;

const char* stage_flag(ShaderStage stage) {
    switch (stage) {
    case ShaderStage::Vertex:
        return "vert";
    case ShaderStage::Fragment:
        return "frag";
    case ShaderStage::Compute:
        return "comp";
    }
    return "frag";
}

std::string read_text(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    constexpr size_t kMax = 8000; // enough to see the errors, not a whole disassembly
    if (text.size() > kMax) text = text.substr(0, kMax) + "\n[...]";
    return text;
}

// Runs argv[0] from PATH with stdout/stderr sent to files in `dir`; "" on success.
std::string run(const std::vector<std::string>& argv, const fs::path& dir) {
    const fs::path out_path = dir / (argv[0] + ".stdout");
    const fs::path err_path = dir / (argv[0] + ".stderr");
    std::vector<char*> args;
    for (const auto& a : argv)
        args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_path.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_path.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid = 0;
    const int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) return argv[0] + ": cannot start: " + std::strerror(rc);

    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) return argv[0] + ": waitpid failed: " + std::strerror(errno);
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return {};

    std::string why = WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                        : "killed by signal " + std::to_string(WTERMSIG(status));
    std::string output = read_text(err_path);
    if (output.find_first_not_of(" \t\r\n") == std::string::npos) output = read_text(out_path);
    return argv[0] + ": " + why + "\n" + output;
}

} // namespace

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
    const std::string stage = stage_flag(request.stage);
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
        result.error = run(step, dir);
        if (!result.error.empty()) return result;
    }
    result.ok = true;
    return result;
}

} // namespace watergen
