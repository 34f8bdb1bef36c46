#include "watergen/toolchain/child_process.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>

extern char** environ;

namespace watergen {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    constexpr size_t kMax = 8000; // enough to see the errors, not a whole disassembly
    if (text.size() > kMax) text = text.substr(0, kMax) + "\n[...]";
    return text;
}

} // namespace

std::string run_child_process(const std::vector<std::string>& argv, const fs::path& dir,
                              const std::vector<std::string>& env) {
    const std::string name = fs::path(argv[0]).filename().string();
    const fs::path out_path = dir / (name + ".stdout");
    const fs::path err_path = dir / (name + ".stderr");
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
    // This environment minus the variables `env` sets, then `env`.
    std::vector<char*> envp;
    for (char** e = environ; *e; ++e) {
        const std::string_view entry(*e);
        bool overridden = false;
        for (const auto& set : env)
            overridden = overridden || entry.substr(0, entry.find('=') + 1) ==
                                           std::string_view(set).substr(0, set.find('=') + 1);
        if (!overridden) envp.push_back(*e);
    }
    for (const auto& set : env)
        envp.push_back(const_cast<char*>(set.c_str()));
    envp.push_back(nullptr);
    const int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), envp.data());
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

} // namespace watergen
