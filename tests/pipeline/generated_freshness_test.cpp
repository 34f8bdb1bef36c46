#include <catch2/catch.hpp>

#include "build_test_support.h"
#include "watergen/pipeline/build/build_output.h"

using namespace watergen;
using namespace watergen::test;

// generated/ in the repository is exactly what `watergen build` writes today for the example
// material and scenes (scripts/regenerate rewrites it): fresh, and deterministic.
TEST_CASE("generated_files_match_the_generator", "[determinism]") {
    const auto expected = reference_build();
    const auto on_disk = read_tree(source_dir() + "/generated");
    INFO("run scripts/regenerate");
    for (const auto& [path, bytes] : expected) {
        INFO(path);
        auto it = on_disk.find(path);
        CHECK(it != on_disk.end());
        if (it != on_disk.end()) CHECK(it->second == bytes);
    }
    for (const auto& [path, bytes] : on_disk) {
        INFO(path);
        CHECK(expected.count(path) == 1);
    }
}
