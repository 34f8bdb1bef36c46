#include <catch2/catch.hpp>

#include "watergen/plan/json_reader.h"

using namespace watergen;

namespace {

JsonSource parsed(const std::string& text) {
    Diagnostic error;
    auto src = JsonSource::parse(text, "r.json", &error);
    REQUIRE(src);
    return *src;
}

} // namespace

TEST_CASE("json_reader_reads_typed_values_and_reports_where_each_was", "[json]") {
    const JsonSource src =
        parsed("{\"s\": \"a\", \"b\": true, \"n\": 2.5, \"list\": [\"x\", \"y\"],\n"
               " \"v\": [1, 2], \"one\": 3, \"r\": {\"min\": 1, \"max\": 2}}");
    Diagnostics ds;
    JsonReader r(src, ds);
    std::vector<std::string> read;
    r.on_read([&](const std::string& pointer) { read.push_back(pointer); });
    std::string s;
    bool b = false;
    double n = 0, lo = 0, hi = 0;
    std::vector<std::string> list;
    std::vector<double> v, one;
    REQUIRE(r.keys("", {"s", "b", "n", "list", "v", "one", "r"}, {"s"}));
    REQUIRE(r.string("/s", s));
    REQUIRE(r.boolean("/b", b));
    REQUIRE(r.number("/n", n));
    REQUIRE(r.strings_in("/list", {"x", "y", "z"}, list));
    REQUIRE(r.numbers("/v", v, 1));
    REQUIRE(r.numbers("/one", one, 1));
    const NumberBounds bounds{0, 10, "m"};
    REQUIRE(r.range("/r", lo, hi, &bounds));
    CHECK(ds.empty());
    CHECK(s == "a");
    CHECK(b);
    CHECK(n == 2.5);
    CHECK(list == std::vector<std::string>{"x", "y"});
    CHECK(v == std::vector<double>{1, 2});
    CHECK(one == std::vector<double>{3});
    CHECK(lo == 1);
    CHECK(hi == 2);
    CHECK(r.members("") == std::vector<std::string>{"s", "b", "n", "list", "v", "one", "r"});
    CHECK(read == std::vector<std::string>{"/s", "/b", "/n", "/list/0", "/list/1", "/list", "/v/0",
                                           "/v/1", "/v", "/one", "/r/min", "/r/max", "/r"});
}

TEST_CASE("json_reader_errors_name_the_value_and_what_was_expected", "[json]") {
    const JsonSource src =
        parsed("{\"s\": 1, \"list\": [\"x\", \"x\"], \"v\": [], \"r\": {\"min\": 1, \"max\": 20}}");
    auto error_of = [&](const std::function<bool(JsonReader&)>& read) {
        Diagnostics ds;
        JsonReader r(src, ds);
        CHECK_FALSE(read(r));
        REQUIRE(ds.size() == 1);
        return format_diagnostic(ds[0]);
    };
    std::string s;
    std::vector<std::string> list;
    std::vector<double> v;
    double lo = 0, hi = 0;
    CHECK(error_of([&](JsonReader& r) {
              return r.keys("", {"s", "list", "v", "r"}, {"s", "t"}, "(see docs/user-guide.md)");
          }) == "r.json:1:1: error: /: missing key 't' (see docs/user-guide.md)");
    CHECK(error_of([&](JsonReader& r) {
              return r.keys("", {"s", "v"}, {});
          }) == "r.json:1:10: error: /list: unknown key 'list'; expected one of s, v");
    CHECK(error_of([&](JsonReader& r) { return r.string("/s", s); }) ==
          "r.json:1:2: error: /s: expected a string, got a number (1)");
    CHECK(error_of([&](JsonReader& r) {
              return r.strings_in("/list", {"x", "y"}, list);
          }) == "r.json:1:24: error: /list/1: 'x' is listed twice");
    CHECK(error_of([&](JsonReader& r) { return r.numbers("/v", v, 1); }) ==
          "r.json:1:30: error: /v: expected a number or an array of numbers, got an array");
    const NumberBounds bounds{0, 10, "m"};
    CHECK(error_of([&](JsonReader& r) { return r.range("/r", lo, hi, &bounds); }) ==
          "r.json:1:55: error: /r/max: 20 m is out of range; expected a value in [0, 10] m");
    CHECK(error_of([&](JsonReader& r) {
              return r.object("/v", "an object mapping names to values");
          }) == "r.json:1:30: error: /v: expected an object mapping names to values, got an array");
}
