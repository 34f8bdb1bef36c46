#include <catch2/catch.hpp>

#include "watergen/plan/json_source.h"

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
