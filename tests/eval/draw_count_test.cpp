// Reading callgrind's dumps: each client-request dump gives its label and its totals line.
#include <catch2/catch.hpp>

#include "watergen/eval/measure/draw_count.h"

using namespace watergen;

TEST_CASE("a_client_request_dump_gives_its_label_and_total_instructions", "[cost]") {
    // The shape callgrind 3.19 writes (abridged); "summary:" misses the other threads' work
    // after instrumentation was switched off and on, so the totals line is the count.
    const std::string dump = "# callgrind format\nversion: 1\ncreator: callgrind-3.19.0\n"
                             "pid: 6207\ncmd:  watergen cost --counted\npart: 2\n\n"
                             "desc: Trigger: Client Request: hlsl\n\npositions: line\n"
                             "events: Ir\nsummary: 28556\n\nfl=(1) ???\nfn=(1) f\n0 7178062\n\n"
                             "totals: 7178062\n";
    const auto c = parse_callgrind_dump(dump);
    REQUIRE(c);
    CHECK(c->label == "hlsl");
    CHECK(c->instructions == 7178062u);
}

TEST_CASE("a_dump_no_client_request_triggered_is_not_a_draw", "[cost]") {
    CHECK_FALSE(parse_callgrind_dump("desc: Trigger: Program termination\ntotals: 11\n"));
    CHECK_FALSE(parse_callgrind_dump("desc: Trigger: Client Request: glsl\nsummary: 5\n"));
    CHECK_FALSE(parse_callgrind_dump(""));
}
