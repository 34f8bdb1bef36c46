#include <catch2/catch.hpp>

#include "watergen/eval/bench/stability_bench.h"

using namespace watergen;

// What an earlier commit's bench wrote, in its own column order, joins to this run's rows by
// case and point; a row of another point or case joins nothing.
TEST_CASE("a_before_csv_joins_by_case_and_point", "[bench][stability]") {
    const std::string csv =
        "view,variant,waves,precision,geometry,size,sweep,time_s,offset_m,elevation_degrees,"
        "glsl_vs_cpu_double_max_abs,glsl_de00_p99,strict_half_max_abs\n"
        "sun_glint,\"a,b\",gerstner,full,screen_pass,512,view,604800,100000,0,1.03,0.98,\n"
        "grazing,k,gerstner,half,screen_pass,512,elevation,0,0,0.5,0.0029,0.01,0.004\n";
    std::string error;
    const auto table = parse_stability_before(csv, "old.csv", error);
    INFO(error);
    REQUIRE(table);
    REQUIRE(table->size() == 2);
    const StabilityCase full{"gerstner", "full", "screen_pass", 512},
        half{"gerstner", "half", "screen_pass", 512};
    const auto corner =
        table->find(stability_join_key(full, StabilityPoint{"view", "sun_glint", 604800, 1e5, 0}));
    REQUIRE(corner != table->end());
    CHECK(corner->second.max_abs == 1.03);
    CHECK(corner->second.de00_p99 == 0.98);
    CHECK(std::isnan(corner->second.strict_max_abs));
    const auto low =
        table->find(stability_join_key(half, StabilityPoint{"elevation", "grazing", 0, 0, 0.5}));
    REQUIRE(low != table->end());
    CHECK(low->second.strict_max_abs == 0.004);
    CHECK(table->count(
              stability_join_key(half, StabilityPoint{"view", "sun_glint", 604800, 1e5, 0})) == 0);
}

TEST_CASE("a_before_csv_that_is_not_one_is_refused_at_its_line", "[bench][stability]") {
    const std::string head = "waves,precision,geometry,size,sweep,time_s,offset_m,"
                             "elevation_degrees,view,glsl_vs_cpu_double_max_abs,glsl_de00_p99\n";
    std::string error;
    CHECK_FALSE(parse_stability_before("", "e.csv", error));
    CHECK(error == "e.csv:1: empty: expected a stability.csv header");
    CHECK_FALSE(parse_stability_before("waves,size\n", "h.csv", error));
    CHECK(error.find("h.csv:1: no column 'precision'") == 0);
    CHECK_FALSE(parse_stability_before(
        head + "gerstner,full,screen_pass,512,view,0,0,0,sun_glint,x,0\n", "n.csv", error));
    CHECK(error == "n.csv:2: glsl_vs_cpu_double_max_abs 'x': expected a number");
    CHECK_FALSE(parse_stability_before(head + "gerstner,full\n", "f.csv", error));
    CHECK(error == "f.csv:2: 2 fields, expected 11 (as the header)");
    const std::string row = "gerstner,full,screen_pass,512,view,0,0,0,sun_glint,0.1,0\n";
    CHECK_FALSE(parse_stability_before(head + row + row, "d.csv", error));
    CHECK(error.find("d.csv:3: a second row for gerstner full screen_pass 512 view") == 0);
    CHECK_FALSE(read_stability_before("/nonexistent/stability.csv", error));
    CHECK(error == "/nonexistent/stability.csv: cannot open for reading");
}
