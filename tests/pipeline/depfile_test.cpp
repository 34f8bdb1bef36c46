#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sys/stat.h>
#include <sys/wait.h>

#include "build_test_support.h"
#include "watergen/pipeline/output/depfile.h"

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
    CHECK(*escape_depfile_path("c:d/s.json") == "c\\:d/s.json"); // a bare ':' ends make's targets
    CHECK_FALSE(escape_depfile_path("a\nb"));
    CHECK_FALSE(escape_depfile_path(""));
    // Neither make nor ninja reads these back, whatever the escaping: refused.
    for (const char* bad :
         {"a\tb", "a;b", "a|b", "a%b", "a=b", "a*b", "a?b", "a\"b", "a'b", "a\rb"}) {
        INFO(bad);
        CHECK_FALSE(escape_depfile_path(bad));
    }
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
    const fs::path inputs = tmp.path / "my inputs #1:a";
    fs::create_directories(inputs);
    const fs::path material = inputs / "ma$terial.json", scene = inputs / "open ocean.json";
    fs::copy_file(source_dir() + "/examples/materials/default.json", material);
    fs::copy_file(source_dir() + "/examples/scenes/open_ocean.json", scene);
    {
        std::ofstream run(tmp.path / "run.sh");
        run << "exec '" << WATERGEN_CLI << "' build 'my inputs #1:a/ma$terial.json' --scene "
            << "'my inputs #1:a/open ocean.json' --out out --depfile out.d --cache cache -q\n";
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
    CHECK(deps.find("\n    my inputs #1:a/ma$terial.json\n") != std::string::npos);
    CHECK(deps.find("\n    my inputs #1:a/open ocean.json\n") != std::string::npos);
    CHECK(run("").find("no work to do") != std::string::npos);
    std::ofstream(scene, std::ios::app) << "\n"; // a changed scene file
    CHECK(run("").find("sh run.sh") != std::string::npos);
}

// GNU make reads the same depfile back (`-include`): a path with ' ', '#', '$' and ':' names one
// prerequisite, so make rebuilds when that file is newer and not otherwise.
TEST_CASE("make_reads_the_depfile_back_with_spaces_hashes_dollars_and_colons", "[depfile]") {
    const TempDir tmp("depfile-make");
    const fs::path dir = tmp.path / "in #1:a";
    fs::create_directories(dir);
    const fs::path input = dir / "s $x.json";
    std::ofstream(input) << "{}";
    REQUIRE(
        !write_depfile((tmp.path / "out.d").string(), "out/manifest.json", {"in #1:a/s $x.json"}));
    std::ofstream(tmp.path / "Makefile") << "out/manifest.json:\n\tmkdir -p out && touch $@\n"
                                         << "-include out.d\n";
    const std::string make = "make -s -C '" + tmp.path.string() + "' out/manifest.json";
    REQUIRE(std::system(make.c_str()) == 0);
    REQUIRE(fs::exists(tmp.path / "out/manifest.json"));
    // Not rebuilt while the input is older; rebuilt once it is newer.
    const std::string query = "make -q -C '" + tmp.path.string() + "' out/manifest.json";
    CHECK(WEXITSTATUS(std::system(query.c_str())) == 0);
    fs::last_write_time(tmp.path / "out/manifest.json",
                        fs::last_write_time(input) - std::chrono::seconds(5));
    CHECK(WEXITSTATUS(std::system(query.c_str())) == 1);
}

// A depfile replaces only what watergen wrote: never an input (by name or by a link), a file
// inside the output or an earlier output, a directory, a FIFO or a file of someone else's.
TEST_CASE("a_depfile_replaces_only_a_depfile_watergen_wrote", "[depfile]") {
    const TempDir tmp("depfile-refusal");
    const fs::path input = tmp.path / "m.json";
    std::ofstream(input) << "{}";
    const std::vector<std::string> inputs = {input.string()};
    const fs::path out = tmp.path / "out";
    auto refusal = [&](const fs::path& file) { return depfile_refusal(file, inputs, out); };
    CHECK(refusal(tmp.path / "new.d") == "");
    REQUIRE(
        !write_depfile((tmp.path / "ours.d").string(), (out / "manifest.json").string(), inputs));
    CHECK(refusal(tmp.path / "ours.d") == "");
    CHECK(refusal(input).find("is the input") != std::string::npos);
    fs::create_symlink(input, tmp.path / "link.json");
    CHECK(refusal(tmp.path / "link.json").find("is the input") != std::string::npos);
    fs::create_hard_link(input, tmp.path / "hard.json");
    CHECK(refusal(tmp.path / "hard.json").find("is the input") != std::string::npos);
    CHECK(refusal(out / "x.d").find("lies inside the output directory") != std::string::npos);
    fs::create_directories(tmp.path / "earlier");
    std::ofstream(tmp.path / "earlier/manifest.json") << R"({"generator": "watergen 0.1.0"})";
    CHECK(refusal(tmp.path / "earlier/manifest.json").find("the output of a watergen build") !=
          std::string::npos);
    CHECK(refusal(tmp.path / "earlier/deps.d").find("the output of a watergen build") !=
          std::string::npos);
    fs::create_directories(tmp.path / "dir");
    CHECK(refusal(tmp.path / "dir").find("is a directory") != std::string::npos);
    REQUIRE(::mkfifo((tmp.path / "fifo").c_str(), 0600) == 0);
    CHECK(refusal(tmp.path / "fifo").find("is a FIFO") != std::string::npos);
    std::ofstream(tmp.path / "Makefile.mine") << "all:\n\ttrue\n";
    CHECK(refusal(tmp.path / "Makefile.mine").find("did not write") != std::string::npos);
    std::ofstream(tmp.path / "other.d") << "main.o: main.c \\\n  main.h\n"; // a compiler's
    CHECK(refusal(tmp.path / "other.d").find("did not write") != std::string::npos);
}
