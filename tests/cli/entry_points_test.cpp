// No exception reaches main: for every subcommand, an exception thrown from the function that
// runs it ends the command with exit 1 and the exception's message on stderr, whatever its type.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cstdio>
#include <map>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.h"

using namespace watergen::cli;

namespace {

// Runs `argv` through the command line with every runner replaced by `thrower`; the exit code
// and what went to stderr.
std::pair<int, std::string> run_throwing(const std::vector<std::string>& words,
                                         const std::function<void()>& thrower) {
    std::vector<std::string> args = {"watergen"};
    args.insert(args.end(), words.begin(), words.end());
    std::vector<char*> argv;
    for (std::string& a : args)
        argv.push_back(a.data());
    std::fflush(stderr);
    std::FILE* capture = std::tmpfile();
    const int saved = ::dup(2);
    ::dup2(::fileno(capture), 2);
    const int code = run_with(static_cast<int>(argv.size()), argv.data(),
                              [&](const std::string&, Runner) -> Runner {
                                  return [&]() -> int {
                                      thrower();
                                      return 0;
                                  };
                              });
    std::fflush(stderr);
    ::dup2(saved, 2);
    ::close(saved);
    std::string err;
    std::rewind(capture);
    for (int c; (c = std::fgetc(capture)) != EOF;)
        err += static_cast<char>(c);
    std::fclose(capture);
    return {code, err};
}

} // namespace

TEST_CASE("an_exception_through_any_command_is_exit_1_with_its_message", "[cli]") {
    // The arguments a command needs before its runner is reached (its required options).
    const std::map<std::string, std::vector<std::string>> required = {
        {"build", {"--out", "o"}},
        {"merge", {"o", "s"}},
        {"gpu-worker", {"dir"}},
        {"explain", {"--scene", "s.json"}},
        {"bench prune", {"--scene", "s.json"}},
        {"probe", {"--node", "fresnel.schlick", "--in", "i.csv", "--out", "o.csv"}},
    };
    const std::vector<std::string> paths = command_paths();
    // Every subcommand: emit, render, ..., the benches, the hidden worker.
    REQUIRE(paths.size() >= 20);
    for (const std::string& path : paths) {
        INFO(path);
        std::vector<std::string> words;
        std::istringstream split(path);
        for (std::string w; split >> w;)
            words.push_back(w);
        if (const auto it = required.find(path); it != required.end())
            words.insert(words.end(), it->second.begin(), it->second.end());
        const auto [code, err] =
            run_throwing(words, [&] { throw std::runtime_error("thrown by " + path); });
        CHECK(code == kFailed);
        CHECK(err == "watergen: error: thrown by " + path + "\n");
    }
    // Other kinds: a library's exception, memory, and something that is no std::exception.
    auto bad_json = [] {
        const auto never = nlohmann::json::parse("{");
        FAIL("parsed " << never.dump());
    };
    const auto [json_code, json_err] = run_throwing({"emit"}, bad_json);
    CHECK(json_code == kFailed);
    CHECK(json_err.rfind("watergen: error: [json.exception.parse_error.101]", 0) == 0);
    const auto [memory_code, memory_err] = run_throwing({"emit"}, [] { throw std::bad_alloc(); });
    CHECK(memory_code == kFailed);
    CHECK(memory_err == "watergen: error: out of memory\n");
    const auto [other_code, other_err] = run_throwing({"emit"}, [] { throw 7; });
    CHECK(other_code == kFailed);
    CHECK(other_err == "watergen: error: an unknown exception\n");
}
