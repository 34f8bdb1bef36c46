// The counting workers' scratch directories: removed on every way out, and those of a process
// that is gone (killed outright) swept by the next count.
#include <catch2/catch.hpp>

#include "build_test_support.h"

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "watergen/eval/measure/scratch_directory.h"

using namespace watergen;
using watergen::test::TempDir;
namespace fs = std::filesystem;

namespace {

// A pid that named a process a moment ago and names none now (reaped).
pid_t pid_of_a_finished_process() {
    const pid_t pid = ::fork();
    if (pid == 0) ::_exit(0);
    int status = 0;
    ::waitpid(pid, &status, 0);
    return pid;
}

} // namespace

TEST_CASE("a_scratch_directory_goes_with_everything_in_it", "[cost]") {
    const TempDir root_tmp("wg-scratch");
    const fs::path root = root_tmp.path;
    fs::path made;
    {
        const ScratchDirectory dir(root, "watergen-count-");
        REQUIRE(dir.error().empty());
        made = dir.path();
        CHECK(made.parent_path() == root);
        CHECK(made.filename().string().rfind("watergen-count-" + std::to_string(::getpid()) + "-",
                                             0) == 0);
        REQUIRE(fs::is_directory(made));
        std::ofstream(made / "callgrind.out.1") << "dump";
        std::ofstream(made / "valgrind.stderr") << "log";
    }
    CHECK_FALSE(fs::exists(made));
    CHECK(fs::is_empty(root));
}

TEST_CASE("a_scratch_directory_under_a_file_says_why_it_cannot_be_made", "[cost]") {
    const TempDir root_tmp("wg-scratch-file");
    const fs::path root = root_tmp.path;
    std::ofstream(root / "plain") << "not a directory";
    const ScratchDirectory dir(root / "plain", "watergen-count-");
    CHECK(dir.error().rfind("cannot create " + (root / "plain").string() + "/watergen-count-", 0) ==
          0);
}

TEST_CASE("the_scratch_of_a_process_that_is_gone_is_swept", "[cost]") {
    const TempDir root_tmp("wg-sweep");
    const fs::path root = root_tmp.path;
    const pid_t gone = pid_of_a_finished_process();
    const fs::path stale = root / ("watergen-count-" + std::to_string(gone) + "-0");
    const fs::path mine = root / ("watergen-count-" + std::to_string(::getpid()) + "-99");
    const fs::path other = root / "watergen-counting-notes";
    for (const fs::path& p : {stale, mine, other}) {
        fs::create_directories(p);
        std::ofstream(p / "callgrind.out.1") << "dump";
    }
    CHECK(sweep_stale_scratch(root, "watergen-count-") == 1);
    CHECK_FALSE(fs::exists(stale));
    CHECK(fs::exists(mine));  // this process is alive
    CHECK(fs::exists(other)); // not a scratch name
}
