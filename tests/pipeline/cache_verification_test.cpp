// A poisoned cache: every kind of damage a hostile or broken cache directory can hold is
// evicted and rebuilt, never copied into the output, and the output equals a --no-cache build.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <sys/wait.h>

#include "build_test_support.h"
#include "watergen/pipeline/build/build_output.h"
#include "watergen/pipeline/variant/variant_build.h"

using namespace watergen;
using namespace watergen::test;
namespace fs = std::filesystem;

namespace {

// Four variants, unpruned: small enough to rebuild in a moment, enough to see that only the
// poisoned entry is rebuilt.
const char* kSmallMaterial = R"({
  "name": "small",
  "axes": {"fresnel": ["schlick", "exact"], "shore": ["hard", "soft"]}
})";

// The small material, its --no-cache output, and a cache filled by one build of it.
struct CacheFixture {
    TempDir dir{"poison-fixture"};
    fs::path material_file = dir.path / "small.json";
    Material material;
    std::map<std::string, std::string> no_cache_output;
    fs::path cache = dir.path / "cache";

    CacheFixture() {
        std::ofstream(material_file) << kSmallMaterial;
        Diagnostics ds;
        auto m = load_material(material_file.string(), ds);
        REQUIRE(m);
        material = *m;
        BuildRequest plain{material, {}, dir.path / "plain", {}};
        REQUIRE(build_material(plain).ok());
        no_cache_output = read_tree(plain.out);
        BuildRequest cached{material, {}, dir.path / "cached", {}};
        cached.options.cache = BuildCache(cache);
        REQUIRE(build_material(cached).ok());
    }
};

const CacheFixture& fixture() {
    static const CacheFixture f;
    return f;
}

// A copy of the filled cache, one entry of it to poison, and a build that reads it.
struct PoisonedCache {
    TempDir tmp;
    fs::path cache, out, entry;

    explicit PoisonedCache(const std::string& name)
        : tmp("poison-" + name), cache(tmp.path / "cache"), out(tmp.path / "out") {
        fs::copy(fixture().cache, cache, fs::copy_options::recursive);
        std::vector<fs::path> entries;
        for (const auto& e : fs::recursive_directory_iterator(cache))
            if (e.path().extension() == ".wgc") entries.push_back(e.path());
        REQUIRE(entries.size() == 4);
        std::sort(entries.begin(), entries.end());
        entry = entries.front();
    }

    std::string read_entry() const { return read_file(entry); }
    void write_entry(const std::string& bytes) const {
        std::ofstream(entry, std::ios::binary | std::ios::trunc) << bytes;
    }

    BuildSummary build() const {
        BuildRequest r{fixture().material, {}, out, {}};
        r.options.cache = BuildCache(cache);
        return build_material(r);
    }

    // The build rebuilt exactly the poisoned entry, said so, and wrote what --no-cache writes.
    void check_rebuilt(const BuildSummary& s) const {
        REQUIRE(s.ok());
        CHECK(s.cache_rejected == 1);
        CHECK(s.built == 1);
        CHECK(s.cached == 3);
        CHECK(read_tree(out) == fixture().no_cache_output);
        // Rebuilt and stored again: the next build takes everything from the cache.
        const BuildSummary again = build();
        CHECK(again.cache_rejected == 0);
        CHECK(again.cached == 4);
        CHECK(read_tree(out) == fixture().no_cache_output);
    }
};

struct RecordSpan {
    size_t header, body, size; // where its name line starts, where its bytes start, how many
};

// The record `name` of an entry: "watergen-cache 2\n<key>\n", then
// "<name>\n<size>\n<hash>\n<bytes>"...
RecordSpan find_record(const std::string& entry, const std::string& name) {
    size_t pos = entry.find('\n', entry.find('\n') + 1) + 1;
    while (pos < entry.size()) {
        const size_t size_line = entry.find('\n', pos) + 1,
                     hash_line = entry.find('\n', size_line) + 1;
        const size_t body = entry.find('\n', hash_line) + 1;
        const size_t size = std::stoul(entry.substr(size_line, hash_line - 1 - size_line));
        if (entry.compare(pos, size_line - 1 - pos, name) == 0) return {pos, body, size};
        pos = body + size;
    }
    FAIL("no record " << name);
    return {};
}

// Replaces the first `from` inside the record `name` by `to`, of the same length, so that
// only the hash can tell.
std::string edit_record(std::string entry, const std::string& name, const std::string& from,
                        const std::string& to) {
    REQUIRE(from.size() == to.size());
    const RecordSpan r = find_record(entry, name);
    const size_t at = entry.find(from, r.body);
    REQUIRE(at + from.size() <= r.body + r.size);
    entry.replace(at, from.size(), to);
    return entry;
}

} // namespace

TEST_CASE("variant_file_names_are_the_files_every_build_writes", "[cache]") {
    std::vector<Variant> variants;
    enumerate(fixture().material.space, [&](const Variant& v) { variants.push_back(v); });
    REQUIRE(variants.size() == 4);
    const VariantBuild b = build_variant(variants.back());
    REQUIRE(b.ok());
    std::vector<std::string> names;
    for (const auto& [path, bytes] : variant_files(b))
        names.push_back(path);
    CHECK(names == variant_file_names());
    CHECK(names.size() == 23); // 2 x 2 stages x (source, 2 SPIR-V, reflection) + GLSL path's
                               // 2 x (GLSL 330, ESSL 300, MSL) + variant.json
}

TEST_CASE("flipped_bytes_in_a_cached_spirv_binary_are_rebuilt", "[cache]") {
    const PoisonedCache p("flip");
    std::string entry = p.read_entry();
    const RecordSpan r = find_record(entry, "glsl/water.frag.opt.spv");
    REQUIRE(r.size > 100);
    for (size_t i = 40; i < 44; ++i)
        entry[r.body + i] = static_cast<char>(entry[r.body + i] ^ 0x5a);
    p.write_entry(entry);
    p.check_rebuilt(p.build());
}

TEST_CASE("a_renamed_main_in_cached_glsl_is_rebuilt", "[cache]") {
    const PoisonedCache p("main");
    p.write_entry(
        edit_record(p.read_entry(), "glsl/water.frag.glsl", "void main()", "void mian()"));
    const BuildSummary s = p.build();
    p.check_rebuilt(s);
    bool warned = false;
    for (const auto& d : s.diagnostics)
        warned |=
            d.severity == Severity::Warning && d.file == p.entry.string() &&
            d.message.find("record 'glsl/water.frag.glsl': content does not match its hash") !=
                std::string::npos;
    CHECK(warned);
}

TEST_CASE("an_edited_cached_variant_json_is_rebuilt", "[cache]") {
    const PoisonedCache p("json");
    p.write_entry(
        edit_record(p.read_entry(), "variant.json", "\"fresnel\": \"", "\"fresnel\":\"\""));
    p.check_rebuilt(p.build());
}

TEST_CASE("a_record_deleted_from_an_entry_is_rebuilt_not_left_missing", "[cache]") {
    const PoisonedCache p("deleted");
    std::string entry = p.read_entry();
    const RecordSpan r = find_record(entry, "hlsl/water.vert.reflect.json");
    entry.erase(r.header, r.body + r.size - r.header);
    p.write_entry(entry);
    p.check_rebuilt(p.build());
}

TEST_CASE("an_extra_record_in_an_entry_is_rebuilt_not_added", "[cache]") {
    const PoisonedCache p("extra");
    p.write_entry(p.read_entry() + cache_record("glsl/extra.frag.glsl", "void main() {}\n"));
    p.check_rebuilt(p.build());
}

TEST_CASE("a_record_named_to_escape_the_output_writes_nothing_outside", "[cache]") {
    const PoisonedCache p("escape");
    // From <out>/unpruned/<variant>/ four levels up is the test's directory.
    p.write_entry(p.read_entry() +
                  cache_record("glsl/../../../../escaped/x.spv", "\x03\x02\x23\x07"));
    p.check_rebuilt(p.build());
    CHECK_FALSE(fs::exists(p.tmp.path / "escaped"));
    std::vector<std::string> beside;
    for (const auto& e : fs::directory_iterator(p.tmp.path))
        beside.push_back(e.path().filename().string());
    std::sort(beside.begin(), beside.end());
    CHECK(beside == std::vector<std::string>{"cache", "out"});
}

TEST_CASE("an_entry_copied_under_another_key_is_rebuilt", "[cache]") {
    const PoisonedCache p("copied");
    fs::path other;
    for (const auto& e : fs::recursive_directory_iterator(p.cache))
        if (e.path().extension() == ".wgc" && e.path() != p.entry) other = e.path();
    REQUIRE_FALSE(other.empty());
    p.write_entry(read_file(other)); // intact, but another variant's files
    p.check_rebuilt(p.build());
}

TEST_CASE("a_fifo_in_place_of_an_entry_does_not_hang_the_build", "[cache]") {
    const PoisonedCache p("fifo");
    fs::remove(p.entry);
    REQUIRE(::mkfifo(p.entry.c_str(), 0644) == 0);
    // In a child process with a deadline: a build that opens the FIFO for reading waits forever.
    const WatergenRun run = run_watergen({"build", "-q", fixture().material_file.string(),
                                          "--cache", p.cache.string(), "--out", p.out.string()},
                                         60);
    REQUIRE_FALSE(run.timed_out);
    CHECK(run.exit_code == 0);
    CHECK(run.out.find("(1 built, 3 cached, 0 shared between scenes, 0 same shader as another "
                       "variant, 0 failed; "
                       "1 cache entry failed verification, rebuilt)") != std::string::npos);
    CHECK(run.err.find("is a FIFO, not a regular file") != std::string::npos);
    CHECK(read_tree(p.out) == fixture().no_cache_output);
    CHECK(fs::is_regular_file(fs::symlink_status(p.entry))); // evicted, then stored again
}

TEST_CASE("a_symlink_to_dev_zero_is_evicted_without_reading_it", "[cache]") {
    const PoisonedCache p("zero");
    fs::remove(p.entry);
    fs::create_symlink("/dev/zero", p.entry);
    const WatergenRun run = run_watergen({"build", "-q", fixture().material_file.string(),
                                          "--cache", p.cache.string(), "--out", p.out.string()},
                                         60);
    REQUIRE_FALSE(run.timed_out);
    CHECK(run.exit_code == 0);
    CHECK(run.out.find("1 cache entry failed verification, rebuilt") != std::string::npos);
    CHECK(run.err.find("is a symbolic link, not a regular file") != std::string::npos);
    CHECK(run.max_rss_kb <
          1024 * 1024); // reading /dev/zero up to any bound of a GB would show here
    CHECK(read_tree(p.out) == fixture().no_cache_output);
    CHECK(fs::is_regular_file(fs::symlink_status(p.entry))); // the link is gone, not followed
    CHECK(fs::is_character_file("/dev/zero"));
}

TEST_CASE("two_builds_at_once_into_one_output_and_one_cache_finish_identical", "[cache]") {
    const PoisonedCache p("concurrent");
    p.write_entry("garbage"); // both builds find it damaged, evict it and store it again
    const std::vector<std::string> args = {
        "build", "-q",          fixture().material_file.string(), "--cache", p.cache.string(),
        "--out", p.out.string()};
    const pid_t a = start_watergen(args), b = start_watergen(args);
    REQUIRE(a > 0);
    REQUIRE(b > 0);
    int status_a = 0, status_b = 0;
    ::waitpid(a, &status_a, 0);
    ::waitpid(b, &status_b, 0);
    CHECK((WIFEXITED(status_a) && WEXITSTATUS(status_a) == 0));
    CHECK((WIFEXITED(status_b) && WEXITSTATUS(status_b) == 0));
    CHECK(read_tree(p.out) == fixture().no_cache_output);
    const BuildSummary after = p.build();
    CHECK(after.cached == 4); // the cache they left is whole
    CHECK(after.cache_rejected == 0);
}
