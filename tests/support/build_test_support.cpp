#include "build_test_support.h"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>

#include "watergen/pipeline/build/build_output.h"

namespace watergen::test {

std::map<std::string, std::string> reference_build() {
    static const std::map<std::string, std::string> tree = [] {
        Diagnostics ds;
        auto material = load_material(source_dir() + "/examples/materials/default.json", ds);
        REQUIRE(material);
        const TempDir tmp("reference");
        BuildRequest r{*material, example_scenes(), tmp.path / "out", {}};
        REQUIRE(build_material(r).ok());
        return read_tree(r.out);
    }();
    return tree;
}

pid_t start_watergen(const std::vector<std::string>& args, const std::string& stdout_path,
                     const std::string& stderr_path,
                     const std::filesystem::path& working_directory) {
    std::string cli = WATERGEN_CLI;
    std::vector<std::string> copy = args;
    std::vector<char*> argv{cli.data()};
    for (auto& a : copy)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    std::fflush(nullptr); // or the child flushes the parent's buffered output a second time
    const pid_t pid = ::fork();
    if (pid == 0) {
        if (!std::freopen(stdout_path.c_str(), "w", stdout) ||
            !std::freopen(stderr_path.c_str(), "w", stderr))
            ::_exit(126);
        if (!working_directory.empty() && ::chdir(working_directory.c_str()) != 0) ::_exit(126);
        ::execv(cli.c_str(), argv.data());
        ::_exit(127);
    }
    return pid;
}

WatergenRun run_watergen(const std::vector<std::string>& args, int timeout_seconds,
                         const std::filesystem::path& working_directory) {
    const TempDir logs("run-logs");
    const pid_t pid = start_watergen(args, (logs.path / "out").string(),
                                     (logs.path / "err").string(), working_directory);
    REQUIRE(pid > 0);
    WatergenRun run;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_seconds);
    int status = 0;
    struct rusage usage {};
    while (::wait4(pid, &status, WNOHANG, &usage) == 0) {
        if (std::chrono::steady_clock::now() > deadline) {
            run.timed_out = true;
            ::kill(pid, SIGKILL);
            ::wait4(pid, &status, 0, &usage);
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.max_rss_kb = usage.ru_maxrss;
    run.out = read_file(logs.path / "out");
    run.err = read_file(logs.path / "err");
    return run;
}

} // namespace watergen::test
