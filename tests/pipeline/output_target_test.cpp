// `watergen build --out`: it replaces only what watergen wrote, an empty directory or nothing;
// anything else is refused with exit 2 and left as it was, and every error carries its errno.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include "build_test_support.h"
#include "watergen/pipeline/build/build_output.h"
#include "watergen/pipeline/output/output_target.h"
#include "watergen/pipeline/output/output_writer.h"

using namespace watergen;
using namespace watergen::test;
namespace fs = std::filesystem;

namespace {

// One variant: a build takes a fraction of a second.
std::string small_material() {
    return source_dir() + "/tests/cli/data/full_precision.json";
}

WatergenRun build_into(const std::string& out, const fs::path& working_directory = {}) {
    return run_watergen({"build", "-q", "--no-cache", small_material(), "--out", out}, 120,
                        working_directory);
}

// Names in `dir`, sorted: a refused build leaves no staging directory beside the output.
std::vector<std::string> names_in(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir))
        names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

void check_refused(const WatergenRun& run, const std::string& why) {
    INFO(run.err);
    CHECK(run.exit_code == 2);
    CHECK(run.err.find(why) != std::string::npos);
    CHECK(run.out.empty()); // no summary claiming an output
}

} // namespace

TEST_CASE("out_refuses_a_regular_file_and_leaves_it", "[out]") {
    const TempDir tmp("out-file");
    std::ofstream(tmp.path / "notes.txt") << "not a directory\n";
    check_refused(build_into((tmp.path / "notes.txt").string()),
                  "the output directory is a regular file; a build replaces only");
    CHECK(read_file(tmp.path / "notes.txt") == "not a directory\n");
    CHECK(names_in(tmp.path) == std::vector<std::string>{"notes.txt"});
}

TEST_CASE("out_refuses_a_device_or_fifo_and_leaves_it", "[out]") {
    check_refused(build_into("/dev/null"), "the output directory is a character device");
    CHECK(fs::is_character_file("/dev/null"));
    const TempDir tmp("out-fifo");
    REQUIRE(::mkfifo((tmp.path / "pipe").c_str(), 0644) == 0);
    check_refused(build_into((tmp.path / "pipe").string()), "the output directory is a FIFO");
    CHECK(fs::is_fifo(tmp.path / "pipe"));
    CHECK(names_in(tmp.path) == std::vector<std::string>{"pipe"});
}

TEST_CASE("out_refuses_a_directory_of_unrelated_files_and_leaves_it", "[out]") {
    const TempDir tmp("out-unrelated");
    fs::create_directories(tmp.path / "photos" / "2023");
    std::ofstream(tmp.path / "photos" / "2023" / "beach.jpg") << "jpeg";
    std::ofstream(tmp.path / "photos" / "manifest.json")
        << "{\"generator\": \"someone else\"}\n"; // not watergen's
    const auto before = read_tree(tmp.path);
    check_refused(build_into((tmp.path / "photos").string()),
                  "is a directory of files watergen did not write");
    CHECK(read_tree(tmp.path) == before);
    CHECK(names_in(tmp.path) == std::vector<std::string>{"photos"});
}

TEST_CASE("out_refuses_a_symbolic_link_even_to_an_earlier_output", "[out]") {
    const TempDir tmp("out-link");
    REQUIRE(build_into((tmp.path / "real").string()).exit_code == 0);
    const auto real = read_tree(tmp.path / "real");
    fs::create_directory_symlink(tmp.path / "real", tmp.path / "link");
    check_refused(build_into((tmp.path / "link").string()),
                  "the output directory is a symbolic link");
    CHECK(fs::is_symlink(tmp.path / "link"));
    CHECK(read_tree(tmp.path / "real") == real);
}

TEST_CASE("out_dot_and_dotdot_inside_unrelated_files_are_refused", "[out]") {
    const TempDir tmp("out-dot");
    fs::create_directories(tmp.path / "work");
    std::ofstream(tmp.path / "work" / "thesis.tex") << "\\documentclass{article}\n";
    const auto before = read_tree(tmp.path);
    check_refused(build_into(".", tmp.path / "work"), ".: error: the output directory (" +
                                                          (tmp.path / "work").string() +
                                                          ") is the current directory or holds it");
    check_refused(build_into("..", tmp.path / "work"), "is the current directory or holds it");
    CHECK(read_tree(tmp.path) == before);
    CHECK(names_in(tmp.path) == std::vector<std::string>{"work"});
}

TEST_CASE("out_empty_is_a_usage_error", "[out]") {
    check_refused(build_into(""), "the output directory is an empty path");
}

TEST_CASE("out_below_a_regular_file_names_the_errno", "[out]") {
    const TempDir tmp("out-enotdir");
    std::ofstream(tmp.path / "file") << "x";
    check_refused(build_into((tmp.path / "file" / "out").string()),
                  "cannot be inspected: Not a directory");
    CHECK(read_file(tmp.path / "file") == "x");
}

TEST_CASE("out_with_a_trailing_slash_is_the_directory_itself", "[out]") {
    const TempDir tmp("out-slash");
    REQUIRE(build_into((tmp.path / "plain").string()).exit_code == 0);
    const WatergenRun run = build_into("out/", tmp.path);
    INFO(run.err);
    CHECK(run.exit_code == 0);
    CHECK(run.out.find("-> out/ (25 files)") != std::string::npos);
    CHECK(read_tree(tmp.path / "out") == read_tree(tmp.path / "plain"));
    CHECK(build_into("out/", tmp.path).exit_code == 0); // and it replaces its own output again
    CHECK(names_in(tmp.path) == std::vector<std::string>{"out", "plain"});
}

TEST_CASE("out_replaces_an_earlier_output_and_an_empty_directory", "[out]") {
    const TempDir tmp("out-previous");
    const fs::path out = tmp.path / "out";
    fs::create_directories(out);
    REQUIRE(build_into(out.string()).exit_code == 0); // empty: replaced
    const auto first = read_tree(out);
    REQUIRE(first.count("manifest.json") == 1);
    std::ofstream(out / "unpruned" / "stale.txt") << "from an older build\n";
    const WatergenRun again = build_into(out.string());
    CHECK(again.exit_code == 0);
    CHECK(read_tree(out) == first); // replaced as a whole: the stale file is gone
    CHECK(names_in(tmp.path) == std::vector<std::string>{"out"});
}

TEST_CASE("check_output_target_resolves_the_path_and_knows_watergen_manifests", "[out]") {
    const TempDir tmp("out-check");
    const OutputTarget slash = check_output_target(tmp.path.string() + "/a/../out/");
    CHECK(slash.ok());
    CHECK(slash.path == tmp.path / "out");
    CHECK(is_watergen_manifest("{\"generator\": \"watergen 0.1.0\", \"variants\": []}"));
    CHECK_FALSE(is_watergen_manifest("{\"generator\": \"other 1.0\"}"));
    CHECK_FALSE(is_watergen_manifest("watergen 0.1.0"));
    CHECK(is_watergen_manifest(read_file(source_dir() + "/generated/manifest.json")));
}

TEST_CASE("a_failed_commit_names_the_errno_of_the_failing_call", "[out]") {
    const TempDir tmp("out-commit");
    const fs::path out = tmp.path / "out";
    fs::create_directories(out);
    std::ofstream(out / "kept.txt") << "kept\n";
    std::string error;
    const fs::path staging = make_staging_directory(out, &error);
    REQUIRE_FALSE(staging.empty());
    // "out/" moves aside into itself: EINVAL, which the old code reported as "Success".
    const auto e = commit_directory(staging, out.string() + "/");
    REQUIRE(e);
    CHECK(e->find("cannot move aside " + out.string() + "/: Invalid argument") !=
          std::string::npos);
    CHECK(read_tree(out) == std::map<std::string, std::string>{{"kept.txt", "kept\n"}});
    CHECK(names_in(tmp.path) == std::vector<std::string>{"out"});
}

TEST_CASE("build_material_refuses_an_unrelated_output_before_building", "[out]") {
    const TempDir tmp("out-library");
    std::ofstream(tmp.path / "notes.txt") << "mine\n";
    Diagnostics ds;
    auto material = load_material(small_material(), ds);
    REQUIRE(material);
    BuildRequest request; // (aggregate-initialised, GCC 12 warns of an uninitialised member)
    request.material = *material;
    request.out = tmp.path / "notes.txt";
    const BuildSummary s = build_material(request);
    CHECK(s.bad_input);
    CHECK(s.variants == 0); // refused before any variant was built
    REQUIRE(s.diagnostics.size() == 1);
    CHECK(s.diagnostics[0].file == (tmp.path / "notes.txt").string());
    CHECK(s.diagnostics[0].message.rfind("the output directory is a regular file", 0) == 0);
    CHECK(read_file(tmp.path / "notes.txt") == "mine\n");
}
