#include <catch2/catch.hpp>

#include <sys/resource.h>

#include <filesystem>
#include <fstream>

#include "watergen/plan/binding_map_file.h"
#include "watergen/plan/json_source.h"
#include "watergen/plan/material.h"

using namespace watergen;

TEST_CASE("json_positions_point_at_keys_and_elements", "[json]") {
    const std::string text = "{\n"
                             "  \"name\": \"x\",\n"
                             "  \"axes\": {\n"
                             "    \"fresnel\": [\"schlick\", \"exact\"],\n"
                             "    \"n\": 12.5,\n"
                             "    \"a~b/c\": true\n"
                             "  }\n"
                             "}\n";
    Diagnostic error;
    const auto src = JsonSource::parse(text, "m.json", &error);
    REQUIRE(src);
    CHECK(src->position("").line == 1);
    CHECK(src->position("/name").line == 2);
    CHECK(src->position("/name").column == 3);
    CHECK(src->position("/axes/fresnel").line == 4);
    CHECK(src->position("/axes/fresnel/0").column == 17);
    CHECK(src->position("/axes/fresnel/1").column == 28);
    CHECK(src->position("/axes/n").line == 5);
    CHECK(src->position("/axes/a~0b~1c").line == 6);
    // Below a leaf: the nearest recorded ancestor.
    CHECK(src->position("/axes/n/3").line == 5);
    CHECK(src->where("/axes/fresnel/1") == "m.json:4:28");
    const Diagnostic d = src->error("/axes/fresnel/1", "unknown choice");
    CHECK(format_diagnostic(d) == "m.json:4:28: error: /axes/fresnel/1: unknown choice");
}

TEST_CASE("json_number_followed_by_newline_is_on_its_own_line", "[json]") {
    Diagnostic error;
    const auto src = JsonSource::parse("[1,\n 22\n,\n3]", "a.json", &error);
    REQUIRE(src);
    CHECK(src->position("/1").line == 2);
    CHECK(src->position("/1").column == 2);
    CHECK(src->position("/2").line == 4);
}

TEST_CASE("json_syntax_errors_name_line_and_column", "[json]") {
    Diagnostic error;
    CHECK_FALSE(JsonSource::parse("{\n  \"a\": [1, 2,]\n}", "bad.json", &error));
    CHECK(error.file == "bad.json");
    CHECK(error.line == 2);
    CHECK(error.column == 14);
    CHECK(error.message.find("invalid JSON: syntax error") == 0);
    CHECK_FALSE(JsonSource::parse("", "empty.json", &error));
    CHECK(error.line == 1);
    CHECK(error.message.find("invalid JSON") == 0);
}

TEST_CASE("json_duplicate_keys_are_errors", "[json]") {
    Diagnostic error;
    CHECK_FALSE(JsonSource::parse("{\"a\": 1,\n \"a\": 2}", "dup.json", &error));
    CHECK(format_diagnostic(error) == "dup.json:2:2: error: /a: duplicate key 'a'");
}

TEST_CASE("json_missing_file_names_the_path", "[json]") {
    Diagnostic error;
    CHECK_FALSE(JsonSource::load("/no/such/file.json", &error));
    CHECK(format_diagnostic(error) == "/no/such/file.json: error: cannot open the file");
}

namespace {

// Peak resident memory of this process so far, in KiB.
long peak_rss_kib() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss;
}

std::string nested_arrays(size_t depth) {
    return std::string(depth, '[') + std::string(depth, ']');
}

} // namespace

TEST_CASE("json_nested_past_the_depth_limit_is_an_error_found_early", "[json]") {
    // 60k levels once took gigabytes (a JSON pointer stored per level) and then aborted.
    const std::string text = "\n  " + nested_arrays(60000);
    const long before = peak_rss_kib();
    Diagnostic error;
    CHECK_FALSE(JsonSource::parse(text, "deep.json", &error));
    CHECK(peak_rss_kib() - before < 64 * 1024);
    // Stops at the first bracket past the limit: the 65th, on line 2 after two spaces.
    CHECK(format_diagnostic(error) == "deep.json:2:67: error: invalid JSON: nested deeper than 64 "
                                      "levels, the limit for description files");
}

TEST_CASE("json_nested_up_to_the_depth_limit_parses", "[json]") {
    Diagnostic error;
    const auto src = JsonSource::parse(nested_arrays(kMaxJsonDepth), "deep.json", &error);
    REQUIRE(src);
    CHECK(src->root().is_array());
    CHECK_FALSE(JsonSource::parse(nested_arrays(kMaxJsonDepth + 1), "deep.json", &error));
    // Objects count alike.
    std::string objects;
    for (size_t i = 0; i < kMaxJsonDepth; ++i)
        objects += "{\"a\":";
    CHECK(JsonSource::parse(objects + "1" + std::string(kMaxJsonDepth, '}'), "deep.json", &error));
}

TEST_CASE("json_text_past_the_size_limit_is_an_error", "[json]") {
    // A string filling the file up to the limit exactly, then one byte more.
    const std::string fits = "\"" + std::string(kMaxJsonBytes - 2, 'a') + "\"";
    Diagnostic error;
    CHECK(JsonSource::parse(fits, "big.json", &error));
    CHECK_FALSE(JsonSource::parse(fits + " ", "big.json", &error));
    CHECK(format_diagnostic(error) == "big.json:1:4194305: error: the file is larger than 4194304 "
                                      "bytes (4 MiB), the limit for description files");
}

TEST_CASE("json_file_past_the_size_limit_is_an_error", "[json]") {
    const auto path = std::filesystem::temp_directory_path() / "watergen-json-size-test.json";
    {
        std::ofstream out(path, std::ios::binary);
        out << "[\n" << std::string(kMaxJsonBytes, ' ') << "1]";
    }
    Diagnostic error;
    CHECK_FALSE(JsonSource::load(path, &error));
    std::filesystem::remove(path);
    CHECK(error.line == 2);
    CHECK(error.column == static_cast<int>(kMaxJsonBytes) - 1);
    CHECK(error.message.find("larger than 4194304 bytes") != std::string::npos);
}

TEST_CASE("json_byte_order_mark_is_skipped_and_not_counted", "[json]") {
    const std::string text = "{\"name\": \"x\", \"n\": [1, 2]}";
    Diagnostic error;
    const auto plain = JsonSource::parse(text, "m.json", &error);
    const auto marked = JsonSource::parse("\xEF\xBB\xBF" + text, "m.json", &error);
    REQUIRE(plain);
    REQUIRE(marked);
    CHECK(marked->root() == plain->root());
    CHECK(marked->where("/n/1") == "m.json:1:24");
    CHECK(plain->where("/n/1") == "m.json:1:24");
    // Errors on the first line are placed alike too.
    CHECK_FALSE(JsonSource::parse("\xEF\xBB\xBF{\"a\": 1,}", "m.json", &error));
    CHECK(error.column == 9);
}

namespace {

// CPU time of this process so far (user and system), in seconds: what a reader costs, whatever
// else the machine runs.
double cpu_seconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
           1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

// `head`, then lines ",\n  <open>i<close>" for i = 0, 1, ... as many as the description limit
// allows, then `tail`.
std::string filled(const std::string& head, const std::string& open, const std::string& close,
                   const std::string& tail) {
    std::string text = head;
    for (size_t i = 0;; ++i) {
        const std::string line = ",\n  " + open + std::to_string(i) + close;
        if (text.size() + line.size() + tail.size() + 1 > kMaxJsonBytes) break;
        text += line;
    }
    return text + "\n" + tail;
}

} // namespace

// Every description reader is linear in its input: a position is found from a line index made
// once, not by counting lines from the start for each token. At the 4 MiB limit the quadratic
// reader took about 49 minutes (extrapolated from 107 s at 800 KB, main 334ad7f); the linear one
// takes under a second of CPU in a release build (docs/measurements.md, "Hostile inputs"). The
// budget, 20 s of CPU for the three, is 20 times that: it holds under sanitizers and load, and a
// quadratic reader cannot meet it.
TEST_CASE("a_4_MiB_description_is_read_in_linear_time", "[json]") {
    const double start = cpu_seconds();
    // A binding map of about 190,000 resources, refused at the first name no shader reads.
    const std::string map =
        filled("{\"watergen_bindings\": 1, \"resources\": {\"WaterParams\": {\"set\": 0, "
               "\"binding\": 0}",
               "\"r", "\": {\"set\": 0, \"binding\": 1}", "}}");
    Diagnostic error;
    const auto src = JsonSource::parse(map, "map.json", &error);
    REQUIRE(src);
    CHECK(src->position("/resources/r0").line == 2);
    Diagnostics ds;
    CHECK_FALSE(read_binding_map(*src, ds));
    // A material with a list of more than 300,000 choices, refused at index 1.
    const std::string material =
        filled("{\"name\": \"m\", \"axes\": {\"fresnel\": [\"schlick\"", "\"c", "\"", "]}}");
    const auto msrc = JsonSource::parse(material, "m.json", &error);
    REQUIRE(msrc);
    Diagnostics mds;
    CHECK_FALSE(parse_material(*msrc, mds));
    REQUIRE_FALSE(mds.empty());
    CHECK(mds[0].line == 2);
    // A syntax error at the very end: its line is found as fast.
    const std::string broken = filled("[0", "", "", "}");
    CHECK_FALSE(JsonSource::parse(broken, "b.json", &error));
    CHECK(error.line > 300000);
    const double spent = cpu_seconds() - start;
    INFO("CPU seconds: " << spent);
    CHECK(spent < 20.0);
}
