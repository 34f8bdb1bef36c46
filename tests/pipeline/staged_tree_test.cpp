// The staging tree past one run of file records: the records go to its spill file sorted, and the
// list it gives back is the same as a tree that held every record, in path order.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "build_test_support.h"
#include "watergen/pipeline/cache/build_cache.h"
#include "watergen/pipeline/record/staged_tree.h"

using namespace watergen;
using namespace watergen::test;
namespace fs = std::filesystem;

namespace {

struct Listed {
    std::vector<RecordedFile> files;
    size_t count = 0;
    std::string failure;
};

// Writes `paths` (in the order given, the last one as a stream) into a tree that spills every
// `run_files` records, lists it, and commits it to `out`.
Listed write_and_list(const fs::path& out, const std::vector<std::string>& paths,
                      size_t run_files) {
    std::string error;
    auto tree = StagedTree::open(out, &error, run_files);
    REQUIRE(tree);
    for (size_t i = 0; i + 1 < paths.size(); ++i)
        REQUIRE_FALSE(tree->write(paths[i], "bytes of " + paths[i]));
    StagedStream last = tree->stream(paths.back());
    last.write("bytes of ");
    last.write(paths.back());
    REQUIRE_FALSE(last.close());
    Listed l;
    tree->for_each_file([&](const RecordedFile& f) { l.files.push_back(f); });
    l.count = tree->count();
    l.failure = tree->failure();
    REQUIRE_FALSE(tree->commit(out));
    return l;
}

} // namespace

TEST_CASE("a staging tree lists the same files in path order after spilling runs", "[unit]") {
    const TempDir tmp("staged-runs");
    // Out of order, across directories, a top-level file between job directories' names.
    const std::vector<std::string> paths = {"scene/b_variant/glsl/water.frag",
                                            "manifest.json",
                                            "scene/a_variant/variant.json",
                                            "scene/b_variant/variant.json",
                                            "passes/p/pass.json",
                                            "scene/a_variant/glsl/water.vert",
                                            "scene/a/variant.json",
                                            "scene-2/a/variant.json",
                                            "watergen_shaders.h",
                                            "scene/a_variant/glsl/water.frag"};
    const Listed held = write_and_list(tmp.path / "held", paths, 1000);
    const Listed spilled = write_and_list(tmp.path / "spilled", paths, 3); // 3 runs and 1 held
    CHECK(held.failure.empty());
    CHECK(spilled.failure.empty());
    CHECK(held.count == paths.size());
    CHECK(spilled.count == paths.size());
    std::vector<std::string> sorted = paths;
    std::sort(sorted.begin(), sorted.end());
    REQUIRE(spilled.files.size() == paths.size());
    for (size_t i = 0; i < paths.size(); ++i) {
        CHECK(spilled.files[i].path == sorted[i]);
        CHECK(spilled.files[i].path == held.files[i].path);
        CHECK(spilled.files[i].size == held.files[i].size);
        CHECK(spilled.files[i].digest == held.files[i].digest);
        const std::string bytes = "bytes of " + sorted[i];
        CHECK(spilled.files[i].size == bytes.size());
        CHECK(spilled.files[i].digest == file_digest(bytes));
    }
    // The committed tree holds the files written and nothing of the spill file.
    size_t files = 0;
    for (const auto& e : fs::recursive_directory_iterator(tmp.path / "spilled"))
        files += e.is_regular_file() ? 1 : 0;
    CHECK(files == paths.size());
}
