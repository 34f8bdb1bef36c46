// A build directory of the fuzzer process's own (removed when it exits), for the runtime
// readers that open files by path (ShaderBuild::open, ShaderBuild::pass).
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace watergen::fuzz {

struct BuildDir {
    std::filesystem::path path;
    explicit BuildDir(const char* what)
        : path(std::filesystem::temp_directory_path() /
               ("watergen-" + std::string(what) + "-fuzz-" + std::to_string(::getpid()))) {
        std::filesystem::create_directories(path);
    }
    ~BuildDir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    void write(const std::string& relative, const void* data, size_t size) const {
        const std::filesystem::path file = path / relative;
        std::filesystem::create_directories(file.parent_path());
        if (FILE* f = std::fopen(file.c_str(), "wb")) {
            std::fwrite(data, 1, size, f);
            std::fclose(f);
        }
    }
};

} // namespace watergen::fuzz
