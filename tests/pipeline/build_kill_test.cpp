#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include "build_test_support.h"
#include "watergen/pipeline/build/build_output.h"

using namespace watergen;
using namespace watergen::test;
namespace fs = std::filesystem;

namespace {

// Starts watergen with `args`, SIGKILLs it after `delay_ms`, reaps it; whether the signal ended
// it (false: it had finished first).
bool killed_after(const std::vector<std::string>& args, int delay_ms) {
    const pid_t pid = start_watergen(args);
    REQUIRE(pid > 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    return WIFSIGNALED(status);
}

// The previous output in `out`: one scene; the new one: the three example scenes, so old and
// new differ. `restore()` puts the old one back.
struct OldAndNew {
    explicit OldAndNew(const fs::path& out)
        : old_request{default_material(), {example_scenes().back()}, out, {}} {
        REQUIRE(build_material(old_request).ok());
        previous = read_tree(out);
        complete = reference_build();
        REQUIRE(previous != complete);
    }
    void restore() const { REQUIRE(build_material(old_request).ok()); }
    BuildRequest old_request;
    std::map<std::string, std::string> previous, complete;
};

} // namespace

TEST_CASE("a_build_killed_midway_leaves_the_previous_output_intact", "[build]") {
    const TempDir tmp("kill");
    const fs::path out = tmp.path / "out";
    const OldAndNew outputs(out);
    const auto& previous = outputs.previous;
    const auto& complete = outputs.complete;
    const auto scenes = example_scenes();

    std::vector<std::string> args = {"build", "-q", "--no-cache",
                                     source_dir() + "/examples/materials/default.json"};
    for (const auto& p : example_scene_paths()) {
        args.push_back("--scene");
        args.push_back(p);
    }
    args.push_back("--out");
    args.push_back(out.string());
    int killed = 0, finished = 0;
    for (int delay_ms : {10, 60, 150, 300, 500, 700, 900, 1200}) {
        const bool was_killed = killed_after(args, delay_ms);
        killed += was_killed;
        finished += !was_killed;
        const auto now = read_tree(out);
        INFO("killed after " << delay_ms << " ms: " << (was_killed ? "killed" : "finished"));
        // Either the old output or the complete new one; never a mix, never nothing.
        CHECK((now == previous || now == complete));
        if (now == complete) outputs.restore(); // back to the old one
    }
    CHECK(killed > 0);
    // A later build still succeeds and clears what the killed ones left beside the output.
    REQUIRE(build_material(BuildRequest{default_material(), scenes, out, {}}).ok());
    CHECK(read_tree(out) == complete);
    for (const auto& e : fs::directory_iterator(tmp.path))
        CHECK(e.path().filename() == "out");
}

TEST_CASE("a_merge_killed_midway_leaves_the_previous_output_intact", "[build]") {
    const TempDir tmp("kill-merge");
    const fs::path out = tmp.path / "out";
    const OldAndNew outputs(out);
    const auto& previous = outputs.previous;
    const auto& complete = outputs.complete;
    std::vector<std::string> merge = {"merge", "--no-cache", out.string()};
    for (int i = 1; i <= 4; ++i) {
        const fs::path shard = tmp.path / ("shard" + std::to_string(i));
        std::vector<std::string> args = {
            "build",      "-q",
            "--no-cache", source_dir() + "/examples/materials/default.json",
            "--shard",    std::to_string(i) + "/4",
            "--out",      shard.string()};
        for (const auto& p : example_scene_paths())
            args.insert(args.end(), {"--scene", p});
        REQUIRE(run_watergen(args).exit_code == 0);
        merge.push_back(shard.string());
    }
    int killed = 0;
    for (int delay_ms : {1, 5, 10, 20, 30, 45, 60, 90}) {
        killed += killed_after(merge, delay_ms);
        const auto now = read_tree(out);
        INFO("merge killed after " << delay_ms << " ms");
        // The old output or the whole merge, never a mix, never nothing.
        CHECK((now == previous || now == complete));
        if (now == complete) outputs.restore();
    }
    CHECK(killed > 0);
    // A later merge succeeds and clears what the killed ones left beside the output.
    REQUIRE(run_watergen(merge).exit_code == 0);
    CHECK(read_tree(out) == complete);
    for (const auto& e : fs::directory_iterator(tmp.path))
        CHECK(
            (e.path().filename() == "out" || e.path().filename().string().rfind("shard", 0) == 0));
}

TEST_CASE("a_shard_killed_midway_leaves_nothing_a_merge_accepts", "[build]") {
    const TempDir tmp("kill-shard");
    std::vector<std::string> args = {
        "build",   "-q",  "--no-cache", source_dir() + "/examples/materials/default.json",
        "--shard", "1/2", "--out",      (tmp.path / "shard1").string()};
    for (const auto& p : example_scene_paths())
        args.insert(args.end(), {"--scene", p});
    std::vector<std::string> second = args;
    second[5] = "2/2";
    second[7] = (tmp.path / "shard2").string();
    REQUIRE(run_watergen(second).exit_code == 0);
    for (int delay_ms : {20, 100, 250}) {
        if (!killed_after(args, delay_ms)) continue; // it finished first: nothing to check
        INFO("shard killed after " << delay_ms << " ms");
        CHECK_FALSE(fs::exists(tmp.path / "shard1")); // only its staging directory beside
        const WatergenRun m =
            run_watergen({"merge", "--no-cache", (tmp.path / "out").string(),
                          (tmp.path / "shard1").string(), (tmp.path / "shard2").string()});
        CHECK(m.exit_code == 2);
        CHECK(m.err.find("nothing written") != std::string::npos);
        CHECK_FALSE(fs::exists(tmp.path / "out"));
    }
}
