#include <catch2/catch.hpp>

#include <fstream>
#include <sys/stat.h>
#include <sys/wait.h>

#include "build_test_support.h"
#include "watergen/pipeline/record/build_record.h"

using namespace watergen;
using namespace watergen::test;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> build_args(const fs::path& tmp, const std::string& out,
                                    const std::vector<std::string>& scenes) {
    std::vector<std::string> args = {"build",
                                     "-q",
                                     source_dir() + "/examples/materials/default.json",
                                     "--out",
                                     (tmp / out).string(),
                                     "--cache",
                                     (tmp / "cache").string()};
    for (const auto& s : scenes)
        args.insert(args.end(), {"--scene", s});
    return args;
}

// Modification time of a file in nanoseconds: an untouched output keeps it.
long long mtime_ns(const fs::path& p) {
    struct stat st {};
    REQUIRE(::stat(p.c_str(), &st) == 0);
    return st.st_mtim.tv_sec * 1000000000LL + st.st_mtim.tv_nsec;
}

} // namespace

TEST_CASE("records_round_trip_and_refuse_anything_else", "[record]") {
    const BuildRecord r =
        make_record("0123456789abcdef", 2, 2, {{"a/b.spv", "xyz"}, {"m.json", ""}});
    const auto back = parse_record(record_text(r));
    REQUIRE(back);
    CHECK(back->key == r.key);
    CHECK(back->variants == 2);
    REQUIRE(back->files.size() == 2);
    CHECK(back->files[0].path == "a/b.spv");
    CHECK(back->files[0].size == 3);
    CHECK(back->files[0].digest == file_digest("xyz"));
    CHECK_FALSE(parse_record(record_text(r) + "extra"));
    CHECK_FALSE(parse_record(record_text(r).substr(0, 60)));
    std::string escaping = record_text(make_record("k", 1, 1, {{"x", "1"}}));
    escaping.replace(escaping.rfind(" x"), 2, " ../x");
    CHECK_FALSE(parse_record(escaping));
}

// The second build with nothing changed verifies the output and does nothing else; a changed
// byte of an output file, a missing file or a changed scene each rebuild.
TEST_CASE("an_unchanged_build_does_nothing_and_a_damaged_output_is_rebuilt", "[record]") {
    const TempDir tmp("record");
    const std::string scene = (tmp.path / "open_ocean.json").string();
    fs::copy_file(source_dir() + "/examples/scenes/open_ocean.json", scene);
    const auto args = build_args(tmp.path, "out", {scene});
    const fs::path out = tmp.path / "out";
    const WatergenRun first = run_watergen(args);
    REQUIRE(first.exit_code == 0);
    CHECK(first.out.find("16 variants (8 built, 0 cached") != std::string::npos);
    const auto tree = read_tree(out);
    const long long manifest_time = mtime_ns(out / "manifest.json");

    const WatergenRun again = run_watergen(args);
    REQUIRE(again.exit_code == 0);
    CHECK(again.out.find("build: 16 variants up to date (" + std::to_string(tree.size()) +
                         " files verified, nothing rebuilt)") != std::string::npos);
    CHECK(read_tree(out) == tree);
    CHECK(mtime_ns(out / "manifest.json") == manifest_time);

    // One byte changed in place, the size kept: found by the hash, rebuilt from the cache.
    std::string victim;
    for (const auto& [path, bytes] : tree)
        if (path.size() > 4 && path.compare(path.size() - 4, 4, ".spv") == 0) victim = path;
    REQUIRE(!victim.empty());
    {
        std::fstream f(out / victim, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(20);
        f.put(static_cast<char>(tree.at(victim)[20] ^ 1));
    }
    REQUIRE(read_file(out / victim).size() == tree.at(victim).size());
    REQUIRE(read_file(out / victim) != tree.at(victim));
    const WatergenRun damaged = run_watergen(args);
    REQUIRE(damaged.exit_code == 0);
    INFO(damaged.out << damaged.err);
    CHECK(damaged.out.find("up to date") == std::string::npos);
    CHECK(damaged.out.find("(0 built, 8 cached") != std::string::npos);
    CHECK(read_tree(out) == tree);

    fs::remove(out / victim);
    const WatergenRun missing = run_watergen(args);
    CHECK(missing.out.find("up to date") == std::string::npos);
    CHECK(read_tree(out) == tree);
    CHECK(run_watergen(args).out.find("up to date") != std::string::npos);

    std::ofstream(scene, std::ios::app) << " "; // same facts, other bytes: runs, same output
    const WatergenRun touched = run_watergen(args);
    CHECK(touched.out.find("up to date") == std::string::npos);
    CHECK(read_tree(out) == tree);
}

// A binding map file is an input like the scenes: an unchanged one no-ops, a changed one
// rebuilds into the new slots (the cache misses: the sources differ), and a profile named
// instead is another build again.
TEST_CASE("a_changed_binding_map_rebuilds_and_an_unchanged_one_does_nothing", "[record]") {
    const TempDir tmp("record-bindings");
    const fs::path map = tmp.path / "engine.json";
    auto write_map = [&](int set) {
        std::ofstream(map) << "{\"watergen_bindings\": 1, \"base\": \"watergen\", \"resources\": "
                              "{\"WaterParams\": {\"set\": "
                           << set << ", \"binding\": 0, \"hlsl_space\": " << set << "}}}\n";
    };
    write_map(1);
    auto args = build_args(tmp.path, "out", {source_dir() + "/examples/scenes/open_ocean.json"});
    args.insert(args.end(), {"--bindings", map.string()});
    REQUIRE(run_watergen(args).exit_code == 0);
    const std::string first = read_file(tmp.path / "out" / "manifest.json");
    CHECK(first.find("\"map\": \"engine.json\"") != std::string::npos);
    CHECK(run_watergen(args).out.find("up to date") != std::string::npos);

    write_map(2);
    const WatergenRun moved = run_watergen(args);
    REQUIRE(moved.exit_code == 0);
    CHECK(moved.out.find("up to date") == std::string::npos);
    CHECK(moved.out.find("(8 built, 0 cached") != std::string::npos);
    const std::string second = read_file(tmp.path / "out" / "manifest.json");
    CHECK(second != first);
    CHECK(second.find("\"WaterParams\": {\n        \"kind\": \"uniform_block\",\n        "
                      "\"set\": 2") != std::string::npos);

    args.back() = "watergen";
    const WatergenRun profile = run_watergen(args);
    CHECK(profile.out.find("up to date") == std::string::npos);
}

// Two builds at once on one cache directory (cold): both succeed with the same bytes, and a
// third build takes every variant from the entries they stored.
TEST_CASE("two_concurrent_builds_share_one_cache_directory", "[record]") {
    const TempDir tmp("shared-cache");
    const auto scenes = example_scene_paths();
    const pid_t a = start_watergen(build_args(tmp.path, "a", scenes));
    const pid_t b = start_watergen(build_args(tmp.path, "b", scenes));
    for (pid_t pid : {a, b}) {
        int status = 0;
        REQUIRE(::waitpid(pid, &status, 0) == pid);
        CHECK((WIFEXITED(status) && WEXITSTATUS(status) == 0));
    }
    const auto reference = reference_build();
    CHECK(read_tree(tmp.path / "a") == reference);
    CHECK(read_tree(tmp.path / "b") == reference);
    const WatergenRun third = run_watergen(build_args(tmp.path, "c", scenes));
    REQUIRE(third.exit_code == 0);
    INFO(third.out << third.err);
    CHECK(third.out.find("(0 built, 48 cached") != std::string::npos);
    CHECK(third.err.find("verification") == std::string::npos);
    CHECK(read_tree(tmp.path / "c") == reference);
}

// The no-op check cannot be fooled: a record that lost the line of a file the manifest names
// (and the file deleted), a directory of the output swapped for a link to a copy, each rebuild;
// a manifest.json broken in a directory the record shows watergen wrote is rebuilt, not refused.
TEST_CASE("the_no_op_check_holds_the_record_to_the_manifest_and_follows_no_link", "[record]") {
    const TempDir tmp("record-hostile");
    const auto args =
        build_args(tmp.path, "out", {source_dir() + "/examples/scenes/open_ocean.json"});
    const fs::path out = tmp.path / "out";
    REQUIRE(run_watergen(args).exit_code == 0);
    const auto tree = read_tree(out);
    auto up_to_date = [&] {
        const WatergenRun r = run_watergen(args);
        INFO(r.out << r.err);
        CHECK(r.exit_code == 0);
        return r.out.find("up to date") != std::string::npos;
    };
    REQUIRE(up_to_date());

    // One line of the record gone (its count kept consistent), and the file it named deleted.
    fs::path record;
    for (const auto& e : fs::directory_iterator(tmp.path / "cache" / "records"))
        record = e.path();
    auto r = read_record(record);
    REQUIRE(r);
    std::string victim;
    for (const RecordedFile& f : r->files)
        if (f.path.find("water.frag.glsl") != std::string::npos) victim = f.path;
    REQUIRE(!victim.empty());
    std::erase_if(r->files, [&](const RecordedFile& f) { return f.path == victim; });
    std::ofstream(record) << record_text(*r);
    REQUIRE(parse_record(read_file(record)));
    fs::remove(out / victim);
    CHECK_FALSE(up_to_date());
    CHECK(read_tree(out) == tree);
    CHECK(up_to_date());

    // The same for the header, which the manifest does not name: the record must vouch for it.
    auto drop_line = [&](const std::string& path) {
        auto kept = read_record(record);
        REQUIRE(kept);
        const size_t before = kept->files.size();
        std::erase_if(kept->files, [&](const RecordedFile& f) { return f.path == path; });
        REQUIRE(kept->files.size() == before - 1);
        std::ofstream(record) << record_text(*kept);
        REQUIRE(parse_record(read_file(record)));
        fs::remove(out / path);
    };
    drop_line("watergen_shaders.h");
    CHECK_FALSE(up_to_date());
    CHECK(read_tree(out) == tree);
    // A record without its manifest line, and the manifest deleted: the record still shows
    // the rest is watergen's, so the build runs (once) instead of refusing every time.
    drop_line("manifest.json");
    CHECK_FALSE(up_to_date());
    CHECK(read_tree(out) == tree);
    CHECK(up_to_date());

    // A directory of the output (not the last component of any file's path) a link to a copy.
    const fs::path copy = tmp.path / "elsewhere";
    fs::rename(out / "open_ocean", copy);
    fs::create_directory_symlink(copy, out / "open_ocean");
    CHECK_FALSE(up_to_date());
    CHECK(fs::is_directory(fs::symlink_status(out / "open_ocean")));
    CHECK(read_tree(out) == tree);

    // manifest.json broken in place: the record of the last build there vouches for the rest.
    std::ofstream(out / "manifest.json") << "{";
    CHECK_FALSE(up_to_date());
    CHECK(read_tree(out) == tree);
    // A file the record does not know beside a broken manifest: not watergen's alone, refused.
    std::ofstream(out / "manifest.json") << "{";
    std::ofstream(out / "notes.txt") << "mine\n";
    const WatergenRun foreign = run_watergen(args);
    CHECK(foreign.exit_code == 2);
    CHECK(foreign.err.find("did not write") != std::string::npos);
    CHECK(read_file(out / "notes.txt") == "mine\n");
}

TEST_CASE("a_record_covers_the_manifest_only_when_it_names_every_file_the_manifest_names",
          "[record]") {
    const std::string manifest =
        R"({"variants": [{"directory": "s/v", "files": {"glsl": ["s/v/a.glsl"]},
        "passes": {"caustics": {"directory": "passes/p", "files": {"spirv": ["passes/p/b.spv"]}}}}]})";
    BuildRecord r = make_record(
        "k", 1, 1, {{"manifest.json", manifest}, {"s/v/a.glsl", "a"}, {"passes/p/b.spv", "b"}});
    CHECK(record_covers_manifest(r, manifest));
    for (const char* lost : {"manifest.json", "s/v/a.glsl", "passes/p/b.spv"}) {
        BuildRecord less = r;
        std::erase_if(less.files, [&](const RecordedFile& f) { return f.path == lost; });
        INFO(lost);
        CHECK_FALSE(record_covers_manifest(less, manifest));
    }
    CHECK_FALSE(record_covers_manifest(r, "{"));
    // A manifest naming a path outside its directory vouches for nothing.
    CHECK_FALSE(record_covers_manifest(
        r, R"({"variants": [{"directory": "s/v", "files": {"glsl": ["../a.glsl"]}}]})"));
}

TEST_CASE("a_record_read_one_file_at_a_time_vouches_as_the_record_read_whole", "[record]") {
    const TempDir tmp("record-stream");
    const std::string manifest =
        R"({"variants": [{"directory": "s/v", "files": {"glsl": ["s/v/a.glsl", "s/v/c.glsl"]},
        "passes": {"caustics": {"directory": "passes/p", "files": {"spirv": ["passes/p/b.spv"]}}}},
        {"directory": "s/v", "same_as": "v", "files": {"glsl": ["s/v/a.glsl", "s/v/c.glsl"]}}]})";
    const FileMap files = {{"manifest.json", manifest},
                           {"s/v/a.glsl", "a"},
                           {"s/v/c.glsl", "c"},
                           {"passes/p/b.spv", "b"}};
    const fs::path out = tmp.path / "out", file = tmp.path / "r.record";
    for (const auto& [path, bytes] : files) {
        fs::create_directories((out / path).parent_path());
        std::ofstream(out / path) << bytes;
    }
    auto covers = [&](size_t names_per_run, const fs::path& scratch) {
        std::FILE* in = std::fopen((out / "manifest.json").c_str(), "rb");
        REQUIRE(in);
        const bool covered = record_covers_manifest(file, in, scratch, {}, names_per_run);
        std::fclose(in);
        return covered;
    };
    const BuildRecord whole = make_record("k", 2, 2, files);
    store_record(file, whole);
    CHECK(outputs_intact(out, file, 2));
    CHECK(read_record_head(file)->files == 4);
    CHECK(*record_top_entries(file) == std::vector<std::string>{"manifest.json", "passes", "s"});
    for (const size_t per_run : {1, 2, 1000}) // the names in runs of 1 and 2, and held
        CHECK(covers(per_run, tmp.path));
    // Names that fit in memory need no spill file: a cache directory that cannot take one (here
    // missing) still vouches; names that must spill there cannot be matched, and do not vouch.
    CHECK(covers(1000, tmp.path / "missing"));
    CHECK_FALSE(covers(1, tmp.path / "missing"));
    for (const char* lost : {"manifest.json", "s/v/a.glsl", "s/v/c.glsl", "passes/p/b.spv"}) {
        BuildRecord less = whole;
        std::erase_if(less.files, [&](const RecordedFile& f) { return f.path == lost; });
        store_record(file, less);
        INFO(lost);
        CHECK(record_covers_manifest(less, manifest) == covers(1, tmp.path));
        CHECK_FALSE(covers(1, tmp.path));
        CHECK_FALSE(covers(1000, tmp.path));
    }
    // A changed byte; a record whose lines are out of path order (a reader matches in one pass).
    store_record(file, whole);
    std::ofstream(out / "s/v/c.glsl") << "C";
    CHECK_FALSE(outputs_intact(out, file, 2));
    std::string text = record_text(whole);
    const size_t a = text.find(" s/v/a.glsl\n"), c = text.find(" s/v/c.glsl\n");
    std::swap(text[a + 5], text[c + 5]);
    CHECK_FALSE(parse_record(text));
    // Nothing of the covering check's spill file is left beside the record.
    size_t entries = 0;
    for (const auto& e : fs::directory_iterator(tmp.path))
        entries += e.path().filename().string()[0] == '.' ? 1 : 0;
    CHECK(entries == 0);
}
