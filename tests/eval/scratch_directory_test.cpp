// The counting workers' scratch directories: removed on every way out, and those no process
// holds the lock of (killed outright) swept by the next count; never one a live process holds,
// whatever its PID says here.
#include <catch2/catch.hpp>

#include "build_test_support.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "watergen/eval/measure/scratch_directory.h"

using namespace watergen;
using watergen::test::TempDir;
namespace fs = std::filesystem;

namespace {

// A process that holds `dir`'s lock until it is killed, as a count in another PID namespace
// (another container sharing /tmp) does: its PID means nothing here.
pid_t hold_lock(const fs::path& dir) {
    int ready[2];
    REQUIRE(::pipe(ready) == 0);
    const pid_t pid = ::fork();
    if (pid == 0) {
        const int fd = ::open((dir / ".lock").c_str(), O_RDWR | O_CREAT, 0600);
        if (fd < 0 || ::flock(fd, LOCK_EX) != 0) ::_exit(1);
        const char one = 1;
        if (::write(ready[1], &one, 1) != 1) ::_exit(1);
        for (;;)
            ::pause();
    }
    char got = 0;
    REQUIRE(::read(ready[0], &got, 1) == 1);
    ::close(ready[0]);
    ::close(ready[1]);
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
        // mkdtemp's name: the prefix and six characters of its own.
        const std::string name = made.filename().string();
        CHECK(name.rfind("watergen-count-", 0) == 0);
        CHECK(name.size() == std::string("watergen-count-").size() + 6);
        REQUIRE(fs::is_directory(made));
        CHECK(fs::is_regular_file(made / ".lock"));
        std::ofstream(made / "callgrind.out.1") << "dump";
        std::ofstream(made / "valgrind.stderr") << "log";
        // Alive while it is ours: a sweep leaves it.
        CHECK(sweep_stale_scratch(root, "watergen-count-") == 0);
        CHECK(fs::is_directory(made));
        // Two at once get two names.
        const ScratchDirectory second(root, "watergen-count-");
        CHECK(second.path() != made);
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

TEST_CASE("a_scratch_directory_is_swept_when_no_process_holds_its_lock", "[cost]") {
    const TempDir root_tmp("wg-sweep");
    const fs::path root = root_tmp.path;
    const fs::path stale = root / "watergen-count-aaaaaa";    // its process was killed
    const fs::path held = root / "watergen-count-bbbbbb";     // a live count elsewhere
    const fs::path unlocked = root / "watergen-count-cccccc"; // no lock file: not judged
    const fs::path other = root / "watergen-counting-notes";  // not a scratch name
    for (const fs::path& p : {stale, held, unlocked, other}) {
        fs::create_directories(p);
        std::ofstream(p / "callgrind.out.1") << "dump";
    }
    std::ofstream(stale / ".lock");
    const pid_t holder = hold_lock(held);
    CHECK(sweep_stale_scratch(root, "watergen-count-") == 1);
    CHECK_FALSE(fs::exists(stale));
    CHECK(fs::exists(held / "callgrind.out.1"));
    CHECK(fs::exists(unlocked));
    CHECK(fs::exists(other));
    // Its process gone (SIGKILL: nothing of its own ran), the lock is free: the next sweep.
    ::kill(holder, SIGKILL);
    int status = 0;
    ::waitpid(holder, &status, 0);
    CHECK(sweep_stale_scratch(root, "watergen-count-") == 1);
    CHECK_FALSE(fs::exists(held));
}
