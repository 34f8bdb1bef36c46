#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "build_test_support.h"
#include "watergen/pipeline/depfile.h"

using namespace watergen;
using namespace watergen::test;
namespace fs = std::filesystem;

TEST_CASE("depfile_paths_escape_spaces_hashes_dollars_and_backslashes", "[depfile]") {
    CHECK(*escape_depfile_path("scenes/open_ocean.json") == "scenes/open_ocean.json");
    CHECK(*escape_depfile_path("my scenes/a b.json") == "my\\ scenes/a\\ b.json");
    CHECK(*escape_depfile_path("#1/$x.json") == "\\#1/$$x.json");
    CHECK(*escape_depfile_path("a\\ b") == "a\\\\\\ b"); // a literal backslash before a space
    CHECK(*escape_depfile_path("a\\b") == "a\\b");       // elsewhere a backslash is itself
    CHECK(*escape_depfile_path("dir\\") == "dir\\\\");   // trailing: doubled
    CHECK_FALSE(escape_depfile_path("a\nb"));
    CHECK_FALSE(escape_depfile_path(""));
    std::string error;
    CHECK(*depfile_text("out/manifest.json", {"m.json", "s 1.json"}, &error) ==
          "out/manifest.json: \\\n  m.json \\\n  s\\ 1.json\n");
    CHECK_FALSE(depfile_text("out/manifest.json", {"bad\rname"}, &error));
    CHECK(error.find("bad\rname") != std::string::npos);
}

// Ninja reads the depfile `watergen build --depfile` writes back into the very paths it was
// given (spaces, '#' and '$' in them), reruns nothing while they are unchanged, and reruns the
// build when a scene changes.
TEST_CASE("ninja_reads_the_build_depfile_and_reruns_when_a_scene_changes", "[depfile]") {
    const TempDir tmp("depfile-ninja");
    const fs::path inputs = tmp.path / "my inputs #1";
    fs::create_directories(inputs);
    const fs::path material = inputs / "ma$terial.json", scene = inputs / "open ocean.json";
    fs::copy_file(source_dir() + "/examples/materials/default.json", material);
    fs::copy_file(source_dir() + "/examples/scenes/open_ocean.json", scene);
    {
        std::ofstream run(tmp.path / "run.sh");
        run << "exec '" << WATERGEN_CLI << "' build 'my inputs #1/ma$terial.json' --scene "
            << "'my inputs #1/open ocean.json' --out out --depfile out.d --cache cache -q\n";
        std::ofstream ninja(tmp.path / "build.ninja");
        ninja << "rule wg\n  command = sh run.sh\n  depfile = out.d\n  deps = gcc\n"
              << "build out/manifest.json: wg\n";
    }
    const std::string ninja = std::string(WATERGEN_NINJA) + " -C '" + tmp.path.string() + "' ";
    auto run = [&](const std::string& args) {
        const fs::path log = tmp.path / "log";
        REQUIRE(std::system((ninja + args + " > '" + log.string() + "' 2>&1").c_str()) == 0);
        return read_file(log);
    };
    CHECK(run("").find("sh run.sh") != std::string::npos);
    const std::string deps = run("-t deps");
    INFO(deps);
    CHECK(deps.find("out/manifest.json: #deps 2") != std::string::npos);
    CHECK(deps.find("\n    my inputs #1/ma$terial.json\n") != std::string::npos);
    CHECK(deps.find("\n    my inputs #1/open ocean.json\n") != std::string::npos);
    CHECK(run("").find("no work to do") != std::string::npos);
    std::ofstream(scene, std::ios::app) << "\n"; // a changed scene file
    CHECK(run("").find("sh run.sh") != std::string::npos);
}
