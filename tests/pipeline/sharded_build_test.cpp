#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "build_test_support.h"
#include "watergen/pipeline/cache/build_cache.h"
#include "watergen/pipeline/shards/shard_file.h"
#include "watergen/pipeline/shards/sharded_build.h"

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
// A merge holds every shard's file list: paths as interned parts, digests as 16 bytes. Looked
// up and read back, they are the text shard.json gave, in path order ('-' sorts before '/').
TEST_CASE("a_shard_file_list_reads_back_what_it_was_given", "[shard]") {
    const std::vector<std::string> paths = {"manifest.json",
                                            "passes/caustics/pass.json",
                                            "s/a-b/glsl/water.frag.spv",
                                            "s/a/glsl/water.frag.spv",
                                            "s/a/hlsl/water.frag.spv",
                                            "s/a/variant.json",
                                            "shard.json",
                                            "t/a/variant.json"};
    ListedFiles files;
    for (size_t i = 0; i < paths.size(); ++i)
        REQUIRE(files.push_back({paths[i], i * 1000, file_digest(paths[i])}));
    REQUIRE(files.size() == paths.size());
    for (size_t i = 0; i < paths.size(); ++i) {
        CHECK(files.contains(paths[i]));
        const ListedFile f = files[i];
        CHECK(f.path == paths[i]);
        CHECK(f.size == i * 1000);
        CHECK(f.digest == file_digest(paths[i]));
    }
    for (const char* absent : {"", "s", "s/", "s/a", "s/a/", "s/a/glsl", "s/a/glsl/water.frag",
                               "s/a/variant.json/x", "s/a-b/variant.json", "a", "zzz"})
        CHECK_FALSE(files.contains(absent));
    // Only file_digest()'s text is a digest: anything else is refused, not kept.
    const std::string digest = file_digest("x");
    std::string upper = digest;
    std::transform(upper.begin(), upper.end(), upper.begin(), ::toupper);
    for (const std::string& bad : {digest.substr(1), digest + "0", upper, std::string(32, 'g')})
        CHECK_FALSE(files.push_back({"u/a/variant.json", 1, bad}));
    CHECK(files.size() == paths.size());
    std::string why;
    CHECK_FALSE(parse_shard_file(R"({"watergen_shard": 1, "index": 1, "count": 1,
        "toolchain": "t", "inputs": "i", "variants": 0, "shapes": [],
        "files": [["a/b/c", 1, "0123"]]})",
                                 &why));
    CHECK(why == "shard.json: a/b/c's hash '0123' is not 32 lowercase hexadecimal digits (an "
                 "XXH3-128 digest)");
}

TEST_CASE("four_shards_merged_are_byte_identical_to_one_build", "[shard]") {
    const TempDir tmp("shards");
    const std::string material = default_material_path();
    REQUIRE(run_watergen(build_args(tmp.path, material, "one", "")).exit_code == 0);
    const auto one = read_tree(tmp.path / "one");
    CHECK(one == reference_build());
    std::vector<std::string> merge = {"merge", "--cache", (tmp.path / "cache").string(),
                                      (tmp.path / "merged").string()};
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

    // The merge stored one build's record: the same build into its output is a no-op.
    const WatergenRun again = run_watergen(build_args(tmp.path, material, "merged", ""));
    INFO(again.out << again.err);
    CHECK(again.exit_code == 0);
    CHECK(again.out.find("build: 56 variants up to date") != std::string::npos);
    CHECK(read_tree(tmp.path / "merged") == one);

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

namespace {

using OJson = nlohmann::ordered_json;

OJson read_json(const fs::path& p) {
    return OJson::parse(read_file(p));
}

// shard.json's size and hash of every file made to agree with the files again: a shard
// rewritten consistently, as only a deliberate edit would.
void rehash(const fs::path& shard) {
    OJson j = read_json(shard / "shard.json");
    for (auto& f : j["files"]) {
        const std::string bytes = read_file(shard / f[0].get<std::string>());
        f[1] = bytes.size();
        f[2] = file_digest(bytes);
    }
    std::ofstream(shard / "shard.json") << j.dump(1) << "\n";
}

void write_json(const fs::path& p, const OJson& j) {
    std::ofstream(p) << j.dump(2) << "\n";
}

} // namespace

// merge replaces OUT whole, so OUT may not be, hold or lie inside a shard; and it trusts no
// shard: a file shard.json leaves out, a variant dropped (shard.json and manifest rewritten to
// agree), a directory outside the output are each refused with exit 2 and nothing written.
TEST_CASE("merge_refuses_an_out_among_its_shards_and_shards_that_do_not_add_up", "[shard]") {
    const TempDir tmp("shards-hostile");
    const std::string material = default_material_path();
    std::vector<std::string> shards;
    for (const char* i : {"1", "2", "3", "4"}) {
        const std::string name = std::string("s") + i;
        REQUIRE(
            run_watergen(build_args(tmp.path, material, name, std::string(i) + "/4")).exit_code ==
            0);
        shards.push_back((tmp.path / name).string());
    }
    const auto kept = read_tree(shards[0]);
    auto merge = [&](const fs::path& out, std::vector<std::string> dirs) {
        dirs.insert(dirs.begin(), {"merge", out.string()});
        return run_watergen(dirs);
    };
    auto refused = [&](const WatergenRun& r, const std::string& why) {
        INFO(r.out << r.err);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find(why) != std::string::npos);
        CHECK(r.err.find("nothing written") != std::string::npos);
    };
    refused(merge(shards[0], shards), "is the shard " + shards[0]);
    CHECK(read_tree(shards[0]) == kept);
    refused(merge(tmp.path / "s1" / "merged", shards), "lies inside the shard " + shards[0]);
    // OUT an earlier output that holds the shards: the old tree would go, shards with it.
    const fs::path outer = tmp.path / "outer";
    std::vector<std::string> inner;
    fs::create_directories(outer);
    for (const std::string& s : shards) {
        fs::copy(s, outer / fs::path(s).filename(), fs::copy_options::recursive);
        inner.push_back((outer / fs::path(s).filename()).string());
    }
    fs::copy_file(fs::path(shards[0]) / "manifest.json", outer / "manifest.json");
    refused(merge(outer, inner), "holds the shard " + inner[0]);
    CHECK(read_tree(inner[0]) == kept);
    fs::create_directories(tmp.path / "foreign");
    std::ofstream(tmp.path / "foreign" / "notes.txt") << "keep\n";
    refused(merge(tmp.path / "foreign", shards), "a directory of files watergen did not write");

    const fs::path out = tmp.path / "merged";
    auto tampered = [&](const std::string& name) {
        const fs::path copy = tmp.path / (name + ".bad");
        fs::copy(tmp.path / name, copy, fs::copy_options::recursive);
        std::vector<std::string> dirs = shards;
        for (std::string& d : dirs)
            if (fs::path(d).filename() == name) d = copy.string();
        return std::make_pair(copy, dirs);
    };
    {
        // A file of a variant left out of shard.json's list.
        const auto [bad, dirs] = tampered("s2");
        OJson j = read_json(bad / "shard.json");
        auto& files = j["files"];
        for (size_t i = 0; i < files.size(); ++i)
            if (files[i][0].get<std::string>().find("water.frag.glsl") != std::string::npos) {
                files.erase(i);
                break;
            }
        std::ofstream(bad / "shard.json") << j.dump(1) << "\n";
        refused(merge(out, dirs), "which shard.json does not list");
        CHECK_FALSE(fs::exists(out));
    }
    {
        // A variant dropped from the manifest and from shard.json, both rehashed.
        const auto [bad, dirs] = tampered("s3");
        OJson m = read_json(bad / "manifest.json");
        const std::string gone = m["variants"].back()["key"];
        m["variants"].erase(m["variants"].size() - 1);
        write_json(bad / "manifest.json", m);
        OJson j = read_json(bad / "shard.json");
        OJson shapes = OJson::array();
        for (const auto& s : j["shapes"])
            if (s[1] != gone) shapes.push_back(s);
        j["shapes"] = shapes;
        j["variants"] = j["variants"].get<size_t>() - 1;
        std::ofstream(bad / "shard.json") << j.dump(1) << "\n";
        rehash(bad);
        refused(merge(out, dirs), "the build's manifest counts");
        CHECK_FALSE(fs::exists(out));
    }
    {
        // A variant's directory pointing outside the output, rehashed.
        const auto [bad, dirs] = tampered("s4");
        OJson m = read_json(bad / "manifest.json");
        m["variants"][0]["directory"] = "../../../evil";
        write_json(bad / "manifest.json", m);
        rehash(bad);
        refused(merge(out, dirs), "is not a plain relative path");
        CHECK_FALSE(fs::exists(out));
    }
    {
        // A variant moved into a shard whose key range does not hold it.
        const auto [bad, dirs] = tampered("s1");
        OJson m = read_json(bad / "manifest.json");
        const OJson other = read_json(fs::path(shards[1]) / "manifest.json")["variants"][0];
        m["variants"].push_back(other);
        write_json(bad / "manifest.json", m);
        OJson j = read_json(bad / "shard.json");
        j["shapes"].push_back({other["scene"], other["key"], "0"});
        j["variants"] = j["variants"].get<size_t>() + 1;
        std::ofstream(bad / "shard.json") << j.dump(1) << "\n";
        rehash(bad);
        refused(merge(out, dirs), "key range");
        CHECK_FALSE(fs::exists(out));
    }
    const WatergenRun ok = merge(out, shards);
    INFO(ok.err);
    CHECK(ok.exit_code == 0);
}

// Specialized (with frozen modules) and branching builds shard by shader: four shards merged
// are the single build byte for byte, and the build after the merge is a no-op. The example
// scenes make 3 shaders, so a shard of four may be empty, and merges as one. A variant drawn by
// a shader its shard does not hold is refused, as are shards of two modes and variants out of
// order.
TEST_CASE("modes_shards_merged_are_byte_identical_to_one_build", "[shard]") {
    const TempDir tmp("shards-modes");
    const std::string material = default_material_path();
    std::map<std::string, std::vector<std::string>> shards_of;
    for (const std::vector<std::string>& mode :
         {std::vector<std::string>{"--mode", "specialized", "--freeze"},
          std::vector<std::string>{"--mode", "branching"}}) {
        const std::string name = mode[1];
        INFO(name);
        auto args = [&](const std::string& out, const std::string& shard) {
            auto a = build_args(tmp.path, material, out, shard);
            a.insert(a.end(), mode.begin(), mode.end());
            return a;
        };
        REQUIRE(run_watergen(args(name + "-one", "")).exit_code == 0);
        const auto one = read_tree(tmp.path / (name + "-one"));
        std::vector<std::string> merge = {"merge", "--cache", (tmp.path / "cache").string(),
                                          (tmp.path / (name + "-merged")).string()};
        size_t shaders = 0, variants = 0, empty = 0;
        for (int i = 1; i <= 4; ++i) {
            const std::string shard = name + "-" + std::to_string(i);
            REQUIRE(run_watergen(args(shard, std::to_string(i) + "/4")).exit_code == 0);
            const auto m = nlohmann::json::parse(read_file(tmp.path / shard / "manifest.json"));
            shaders += m["shaders"].size();
            variants += m["variants"].size();
            empty += m["shaders"].empty() ? 1 : 0;
            merge.push_back((tmp.path / shard).string());
            shards_of[name].push_back((tmp.path / shard).string());
        }
        CHECK(shaders == 3);
        CHECK(variants == 56);
        CHECK(empty > 0);
        const WatergenRun m = run_watergen(merge);
        INFO(m.out << m.err);
        REQUIRE(m.exit_code == 0);
        CHECK(m.out.find("merge: 4 shards, 56 variants") != std::string::npos);
        const auto merged = read_tree(tmp.path / (name + "-merged"));
        for (const auto& [path, bytes] : one) {
            INFO(path);
            REQUIRE(merged.count(path) == 1);
            CHECK(merged.at(path) == bytes);
        }
        CHECK(merged == one);
        const WatergenRun again = run_watergen(args(name + "-merged", ""));
        INFO(again.out << again.err);
        CHECK(again.out.find("build: 56 variants up to date") != std::string::npos);
    }
    auto refused = [&](std::vector<std::string> dirs, const std::string& why) {
        const fs::path out = tmp.path / "refused";
        dirs.insert(dirs.begin(), {"merge", out.string()});
        const WatergenRun r = run_watergen(dirs);
        INFO(r.err);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find(why) != std::string::npos);
        CHECK_FALSE(fs::exists(out));
    };
    std::vector<std::string> mixed = shards_of["specialized"];
    mixed[3] = shards_of["branching"][3];
    refused(mixed, "built from different inputs");
    // A variant pointed at a shader of another shard, shard.json rehashed to agree.
    std::vector<std::string> dirs = shards_of["specialized"];
    std::string with; // a shard with variants
    for (const std::string& d : dirs)
        if (!read_json(fs::path(d) / "manifest.json")["variants"].empty()) with = d;
    REQUIRE(!with.empty());
    const fs::path bad = tmp.path / "bad-shard";
    fs::copy(with, bad, fs::copy_options::recursive);
    OJson m = read_json(bad / "manifest.json");
    m["variants"][0]["shader"] = "open_ocean/elsewhere";
    write_json(bad / "manifest.json", m);
    rehash(bad);
    std::replace(dirs.begin(), dirs.end(), with, bad.string());
    refused(dirs, "which is no shader of the shard's manifest");
    // The merge joins the shards' variants in one pass: a shard's must be in (scene, key) order.
    const fs::path swapped = tmp.path / "swapped-shard";
    fs::copy(with, swapped, fs::copy_options::recursive);
    OJson s = read_json(swapped / "manifest.json");
    REQUIRE(s["variants"].size() > 1);
    std::swap(s["variants"][0], s["variants"][1]);
    write_json(swapped / "manifest.json", s);
    rehash(swapped);
    std::replace(dirs.begin(), dirs.end(), bad.string(), swapped.string());
    refused(dirs, "is out of order or twice");
}
