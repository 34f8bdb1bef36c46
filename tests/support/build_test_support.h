// Helpers of the build tests: temporary directories, whole trees read into memory, the
// example scenes.
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <unistd.h>

#include "watergen/plan/scene_file.h"

namespace watergen::test {

inline std::string source_dir() {
    const char* s = std::getenv("WATERGEN_SOURCE_DIR");
    REQUIRE(s != nullptr);
    return s;
}

// A fresh directory under the system temp directory, removed at the end of the test.
struct TempDir {
    std::filesystem::path path;
    explicit TempDir(const std::string& name)
        : path(std::filesystem::temp_directory_path() /
               ("watergen-test-" + name + "-" + std::to_string(::getpid()))) {
        std::filesystem::remove_all(path);
        std::filesystem::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
};

// Every regular file below `root`: relative path -> bytes.
inline std::map<std::string, std::string> read_tree(const std::filesystem::path& root) {
    std::map<std::string, std::string> files;
    if (!std::filesystem::is_directory(root)) return files;
    for (const auto& e : std::filesystem::recursive_directory_iterator(root)) {
        if (!e.is_regular_file()) continue;
        std::ifstream in(e.path(), std::ios::binary);
        std::stringstream ss;
        ss << in.rdbuf();
        files[std::filesystem::relative(e.path(), root).generic_string()] = ss.str();
    }
    return files;
}

inline std::vector<std::string> example_scene_paths() {
    std::vector<std::string> paths;
    for (const auto& e : std::filesystem::directory_iterator(source_dir() + "/examples/scenes"))
        if (e.path().extension() == ".json") paths.push_back(e.path().string());
    std::sort(paths.begin(), paths.end());
    return paths;
}

inline std::vector<SceneFacts> example_scenes() {
    std::vector<SceneFacts> scenes;
    for (const auto& p : example_scene_paths()) {
        Diagnostics ds;
        auto s = load_scene(p, ds);
        REQUIRE(s);
        scenes.push_back(*s);
    }
    return scenes;
}

// `watergen build` of the example material for the example scenes, on every thread without a
// cache: built once per test binary, then compared against by every test that needs it.
std::map<std::string, std::string> reference_build();

inline std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Damages a cache entry the way a bad disk would: one bit of its last file's bytes flipped, so
// that only the recorded hash can tell.
inline void flip_a_byte(const std::filesystem::path& path) {
    std::string bytes = read_file(path);
    REQUIRE(bytes.size() > 10);
    bytes[bytes.size() - 10] ^= 0x20;
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// Starts the watergen binary with `args` in a child process, its stdout and stderr going to the
// given files, in `working_directory` unless that is empty; returns its pid.
pid_t start_watergen(const std::vector<std::string>& args,
                     const std::string& stdout_path = "/dev/null",
                     const std::string& stderr_path = "/dev/null",
                     const std::filesystem::path& working_directory = {});

struct WatergenRun {
    bool timed_out = false; // then killed
    int exit_code = -1;     // -1 when killed by a signal
    std::string out, err;
    long max_rss_kb = 0; // of the child: what it read into memory shows here
};

// Runs the watergen binary to completion, killing it after `timeout_seconds`.
WatergenRun run_watergen(const std::vector<std::string>& args, int timeout_seconds = 120,
                         const std::filesystem::path& working_directory = {});

} // namespace watergen::test
