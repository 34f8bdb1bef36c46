#include <catch2/catch.hpp>

#include <fstream>

#include <nlohmann/json.hpp>

#include "build_test_support.h"
#include "watergen/pipeline/sharded_build.h"

using namespace watergen;
using namespace watergen::test;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> build_args(const fs::path& tmp, const std::string& material,
                                    const std::string& out, const std::string& shard) {
    std::vector<std::string> args = {"build",
                                     "-q",
                                     material,
                                     "--out",
                                     (tmp / out).string(),
                                     "--cache",
                                     (tmp / "cache").string()};
    for (const auto& s : example_scene_paths())
        args.insert(args.end(), {"--scene", s});
    if (!shard.empty()) args.insert(args.end(), {"--shard", shard});
    return args;
}

std::string default_material_path() {
    return source_dir() + "/examples/materials/default.json";
}

// Directories of variants with files of their own, per the manifest.
size_t built_directories(const std::map<std::string, std::string>& tree) {
    size_t n = 0;
    const auto manifest = nlohmann::json::parse(tree.at("manifest.json"));
    for (const auto& v : manifest["variants"])
        n += v.contains("same_as") ? 0 : 1;
    return n;
}

} // namespace

TEST_CASE("shard_specs_are_i_of_n", "[shard]") {
    std::string why;
    CHECK(parse_shard("3/4", &why)->index == 3);
    CHECK(parse_shard("1/1", &why)->count == 1);
    for (const char* bad : {"0/4", "5/4", "x/y", "4", "/4", "1/", "-1/4", "1/4/2", ""}) {
        INFO(bad);
        CHECK_FALSE(parse_shard(bad, &why));
        CHECK(why.find("expected I/N") != std::string::npos);
    }
    // Every key in exactly one shard.
    size_t in_some = 0;
    for (const char* key : {"a", "b", "c", "d", "e", "f", "g", "h"})
        for (unsigned i = 1; i <= 3; ++i)
            in_some += in_shard({i, 3}, key) ? 1 : 0;
    CHECK(in_some == 8);
}

// Four shards merged are the single build, byte for byte: the manifest and every file, with
// variants whose shader another shard built pointed at it as one build points them.
TEST_CASE("four_shards_merged_are_byte_identical_to_one_build", "[shard]") {
    const TempDir tmp("shards");
    const std::string material = default_material_path();
    REQUIRE(run_watergen(build_args(tmp.path, material, "one", "")).exit_code == 0);
    const auto one = read_tree(tmp.path / "one");
    CHECK(one == reference_build());
    std::vector<std::string> merge = {"merge", (tmp.path / "merged").string()};
    size_t shard_variants = 0, shard_dirs = 0;
    for (int i = 1; i <= 4; ++i) {
        const std::string name = "shard" + std::to_string(i);
        const WatergenRun r =
            run_watergen(build_args(tmp.path, material, name, std::to_string(i) + "/4"));
        REQUIRE(r.exit_code == 0);
        const auto tree = read_tree(tmp.path / name);
        REQUIRE(tree.count("shard.json") == 1);
        const size_t n = nlohmann::json::parse(tree.at("manifest.json"))["variants"].size();
        CHECK(n > 0);
        CHECK(n < 56);
        shard_variants += n;
        shard_dirs += built_directories(tree);
        merge.push_back((tmp.path / name).string());
    }
    CHECK(shard_variants == 56);
    CHECK(shard_dirs > built_directories(one)); // some shader was built in two shards
    const WatergenRun m = run_watergen(merge);
    INFO(m.out << m.err);
    REQUIRE(m.exit_code == 0);
    CHECK(m.out.find("merge: 4 shards, 56 variants") != std::string::npos);
    const auto merged = read_tree(tmp.path / "merged");
    CHECK(merged.size() == one.size());
    for (const auto& [path, bytes] : one) {
        INFO(path);
        REQUIRE(merged.count(path) == 1);
        CHECK(merged.at(path) == bytes);
    }
    CHECK(merged == one);

    // Refused, nothing written: a shard missing, a shard twice, a shard of another material,
    // a file changed after the shard was built, a directory that is no shard.
    const fs::path out = tmp.path / "refused";
    auto refused = [&](std::vector<std::string> args, const std::string& why) {
        args.insert(args.begin(), {"merge", out.string()});
        const WatergenRun r = run_watergen(args);
        INFO(r.err);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find(why) != std::string::npos);
        CHECK(r.err.find("nothing written") != std::string::npos);
        CHECK_FALSE(fs::exists(out));
    };
    const std::string s1 = (tmp.path / "shard1").string(), s2 = (tmp.path / "shard2").string(),
                      s3 = (tmp.path / "shard3").string(), s4 = (tmp.path / "shard4").string();
    refused({s1, s2, s3}, "shard 4/4 is missing; expected all of 1/4 .. 4/4");
    refused({s1, s2, s3, s4, s2}, "shard 2/4 is given twice");
    refused({s1, s2, s3, s4, (tmp.path / "one").string()}, "no shard.json");
    fs::path other = tmp.path / "other.json";
    {
        std::ifstream in(material);
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        text.replace(text.find("\"default\""), 9, "\"other\"");
        std::ofstream(other) << text;
    }
    REQUIRE(run_watergen(build_args(tmp.path, other.string(), "other4", "4/4")).exit_code == 0);
    refused({s1, s2, s3, (tmp.path / "other4").string()}, "built from different inputs");
    std::ofstream(tmp.path / "shard3" / "manifest.json", std::ios::app) << " ";
    refused({s1, s2, s3, s4}, "shard3: manifest.json does not match the size and hash");
}
