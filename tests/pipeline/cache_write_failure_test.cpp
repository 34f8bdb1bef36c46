// A cache that cannot be written (a full disk, a cache path under a regular file) costs only
// time: no temporary file left behind, one warning on stderr naming the cache and why, the files
// still made. A full disk is RLIMIT_FSIZE here: writes past it fail as on a full disk (EFBIG
// rather than ENOSPC), for root too, which a read-only directory does not stop.
#include <catch2/catch.hpp>

#include "build_test_support.h"

#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "watergen/pipeline/cache/build_cache.h"
#include "watergen/pipeline/output/output_writer.h"

using namespace watergen;
using watergen::test::TempDir;
namespace fs = std::filesystem;

namespace {

// Every regular file under `dir`, relative.
std::vector<std::string> files_under(const fs::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file()) out.push_back(fs::relative(e.path(), dir).string());
    return out;
}

// Writes past `bytes` fail while this lives (SIGXFSZ ignored, so they fail instead of killing).
struct FileSizeLimit {
    rlimit old{};
    void (*old_handler)(int) = nullptr;
    explicit FileSizeLimit(rlim_t bytes) {
        ::getrlimit(RLIMIT_FSIZE, &old);
        old_handler = ::signal(SIGXFSZ, SIG_IGN);
        const rlimit small{bytes, old.rlim_max};
        ::setrlimit(RLIMIT_FSIZE, &small);
    }
    ~FileSizeLimit() {
        ::setrlimit(RLIMIT_FSIZE, &old);
        ::signal(SIGXFSZ, old_handler);
    }
};

// What `f` writes to stderr (fd 2).
template <class F> std::string stderr_of(F f) {
    std::fflush(stderr);
    const fs::path capture =
        fs::temp_directory_path() / ("watergen-stderr-" + std::to_string(::getpid()) + ".txt");
    std::FILE* file = std::fopen(capture.c_str(), "w");
    const int saved = ::dup(2);
    ::dup2(::fileno(file), 2);
    f();
    std::fflush(stderr);
    ::dup2(saved, 2);
    ::close(saved);
    std::fclose(file);
    std::ifstream in(capture);
    std::stringstream text;
    text << in.rdbuf();
    fs::remove(capture);
    return text.str();
}

const FileMap kBig = {{"glsl/a.spv", std::string(64 * 1024, 'x')}, {"variant.json", "{}\n"}};

} // namespace

TEST_CASE("a_store_on_a_full_disk_leaves_no_temporary_file", "[cache]") {
    const TempDir dir_tmp("wg-cache-full");
    const fs::path dir = dir_tmp.path;
    const BuildCache cache(dir / "cache");
    fs::create_directories(dir / "cache" / "01");
    std::optional<std::string> store_error, record_error;
    {
        const FileSizeLimit limit(4096);
        store_error = cache.store("0123456789abcdef", kBig);
        record_error = write_file_atomically(dir / "cache" / "x.record", kBig.at("glsl/a.spv"));
    }
    REQUIRE(store_error);
    CHECK(store_error->rfind("cannot write " + (dir / "cache" / "01").string() + "/", 0) == 0);
    REQUIRE(record_error);
    CHECK(record_error->rfind("cannot write " + (dir / "cache" / "x.record.tmp-").string(), 0) ==
          0);
    CHECK(files_under(dir).empty());
}

TEST_CASE("a_cache_that_cannot_be_written_warns_once_and_the_build_goes_on", "[cache]") {
    const TempDir dir_tmp("wg-cache-under-file");
    const fs::path dir = dir_tmp.path;
    std::ofstream(dir / "plain") << "a regular file, not a directory";
    const BuildCache cache(dir / "plain" / "cache");
    const BuildCache copy = cache; // the build's jobs hold copies: still one warning
    int made = 0;
    auto make = [&]() -> std::optional<FileMap> {
        ++made;
        return kBig;
    };
    const std::vector<std::string> names = {"glsl/a.spv", "variant.json"};
    CacheUse first, second;
    const std::string said = stderr_of([&] {
        first = cache.load_or_make("0123456789abcdef", names, make);
        second = copy.load_or_make("fedcba9876543210", names, make);
    });
    CHECK(made == 2);
    CHECK(first.files == kBig);
    CHECK(second.files == kBig);
    CHECK_FALSE(first.cached);
    CHECK(first.rejected.empty()); // a miss, not a damaged entry
    CHECK(said == "watergen: warning: cache " + (dir / "plain" / "cache").string() +
                      " cannot be written (cannot create " +
                      (dir / "plain" / "cache" / "01").string() +
                      ": Not a directory); building without storing\n");
}
