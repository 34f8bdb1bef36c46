#include <catch2/catch.hpp>

#include <fstream>

#include "build_test_support.h"
#include "watergen/pipeline/cache/build_cache.h"
#include "watergen/pipeline/jobs/parallel_build.h"

using namespace watergen;
using namespace watergen::test;

TEST_CASE("content_hash_covers_parts_their_boundaries_and_the_toolchain", "[cache]") {
    const std::string h = content_hash({"ab", "c"});
    CHECK(h.size() == 16);
    CHECK(h == content_hash({"ab", "c"}));
    CHECK(h != content_hash({"a", "bc"})); // boundaries count
    CHECK(h != content_hash({"ab", "c", ""}));
    CHECK(toolchain_fingerprint().find("glslang 12.") != std::string::npos);
    CHECK(toolchain_fingerprint().find("SPIRV-Tools") != std::string::npos);
}

TEST_CASE("cache_round_trips_binary_files_and_treats_damage_as_a_miss", "[cache]") {
    const TempDir tmp("cache-unit");
    const BuildCache cache(tmp.path);
    const FileMap files = {{"glsl/a.spv", std::string("\x03\x02\x23\x07\0\n\nxyz", 10)},
                           {"variant.json", "{}\n"},
                           {"empty", ""}};
    const std::vector<std::string> names = {"empty", "glsl/a.spv", "variant.json"};
    const auto miss = cache.load("0123456789abcdef", names);
    CHECK_FALSE(miss.files);
    CHECK(miss.rejected.empty()); // no entry: a plain miss
    REQUIRE_FALSE(cache.store("0123456789abcdef", files));
    const auto back = cache.load("0123456789abcdef", names);
    REQUIRE(back.files);
    CHECK(*back.files == files);
    // A truncated entry (a crash while writing cannot leave one, but a full disk might).
    const auto entry = tmp.path / "01" / "0123456789abcdef.wgc";
    CHECK(cache.entry("0123456789abcdef") == entry);
    std::ofstream(entry, std::ios::binary | std::ios::trunc)
        << "watergen-cache 2\n0123456789abcdef\nglsl/a.spv\n999\nabc";
    const auto truncated = cache.load("0123456789abcdef", names);
    CHECK_FALSE(truncated.files);
    CHECK(truncated.rejected == "truncated record header");
    CHECK_FALSE(std::filesystem::exists(entry)); // evicted
    // An entry of the previous format (no hashes) is outdated: a miss, not a failed verification.
    std::ofstream(entry, std::ios::binary | std::ios::trunc) << "watergen-cache 1\nempty\n0\n";
    const auto outdated = cache.load("0123456789abcdef", names);
    CHECK_FALSE(outdated.files);
    CHECK(outdated.rejected.empty());
    CHECK_FALSE(BuildCache().load("0123456789abcdef", names).files); // disabled
}

TEST_CASE("targets_choose_the_files_of_a_variant", "[cache]") {
    const FileMap all = {{"variant.json", ""},
                         {"glsl/water.frag.glsl", ""},
                         {"glsl/water.frag.spv", ""},
                         {"glsl/water.frag.opt.spv", ""},
                         {"glsl/water.frag.330.glsl", ""},
                         {"glsl/water.frag.300es.glsl", ""},
                         {"glsl/water.frag.metal", ""},
                         {"glsl/water.frag.reflect.json", ""},
                         {"hlsl/water.frag.hlsl", ""},
                         {"hlsl/water.frag.spv", ""},
                         {"hlsl/water.frag.330.glsl", ""},
                         {"hlsl/water.frag.reflect.json", ""}};
    auto names = [](const FileMap& m) {
        std::vector<std::string> v;
        for (const auto& [k, _] : m)
            v.push_back(k);
        return v;
    };
    CHECK(names(filter_targets(all, {Target::Essl300})) ==
          std::vector<std::string>{"glsl/water.frag.300es.glsl", "variant.json"});
    CHECK(names(filter_targets(all, {Target::Glsl, Target::Spirv})) ==
          std::vector<std::string>{"glsl/water.frag.glsl", "glsl/water.frag.opt.spv",
                                   "glsl/water.frag.spv", "variant.json"});
    CHECK(names(filter_targets(all, {Target::Hlsl, Target::Spirv, Target::Reflection})) ==
          std::vector<std::string>{"glsl/water.frag.opt.spv", "glsl/water.frag.reflect.json",
                                   "glsl/water.frag.spv", "hlsl/water.frag.hlsl",
                                   "hlsl/water.frag.reflect.json", "hlsl/water.frag.spv",
                                   "variant.json"});
}
