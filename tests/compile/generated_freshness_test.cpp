#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "watergen/covering_array.h"
#include "watergen/variant_build.h"

using namespace watergen;
namespace fs = std::filesystem;

// generated/ in the repository must be exactly what the generator writes today
// (scripts/regenerate rewrites it).
TEST_CASE("generated_files_match_the_generator", "[determinism]") {
    const char* source = std::getenv("WATERGEN_SOURCE_DIR");
    REQUIRE(source != nullptr);
    const fs::path root = fs::path(source) / "generated" / "water";
    REQUIRE(fs::is_directory(root));
    std::set<std::string> expected_dirs;
    for (const Variant& v : pairwise_covering_variants()) {
        INFO(v.key() << " (run scripts/regenerate)");
        expected_dirs.insert(v.file_stem());
        const auto files = variant_files(build_variant(v));
        REQUIRE(!files.empty());
        std::set<std::string> on_disk;
        for (const auto& entry : fs::recursive_directory_iterator(root / v.file_stem()))
            if (entry.is_regular_file()) on_disk.insert(fs::relative(entry.path(), root / v.file_stem()).generic_string());
        std::set<std::string> generated;
        for (const auto& [name, bytes] : files) {
            generated.insert(name);
            std::ifstream in(root / v.file_stem() / name, std::ios::binary);
            std::stringstream ss;
            ss << in.rdbuf();
            INFO(name);
            CHECK(ss.str() == bytes);
        }
        CHECK(on_disk == generated);
    }
    std::set<std::string> dirs;
    for (const auto& entry : fs::directory_iterator(root)) dirs.insert(entry.path().filename().string());
    CHECK(dirs == expected_dirs);
}
