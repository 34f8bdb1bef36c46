// Reading ACO's disassembly (aco_loops.h): instruction lines, loops from back branches, their
// nesting, and the per-pixel estimate that weights each body by its trip count.
#include <catch2/catch.hpp>

#include "watergen/eval/measure/aco_loops.h"

using namespace watergen;

namespace {

// RADV 22.3's layout: labels at the margin, an instruction per tab-indented line, its encoding
// after ';'. Two loops: BB1 (instructions 1-6) around BB2 (3-4).
const char* kNested = R"(BB0:
	s_mov_b32 s0, s3                                            ; be800303
BB1:
	v_add_f32_e32 v0, v0, v1                                    ; 06000300
	s_cbranch_scc1 BB4                                          ; bf850157
BB2:
	v_mul_f32_e32 v1, v1, v2                                    ; 10020502
	s_cbranch_scc0 BB2                                          ; bf84fffe
	v_mov_b32_e32 v3, v1                                        ; 7e060301
	s_branch BB1                                                ; bf82fea7
BB4:
	exp mrt0 v0, v0, v1, v1 done compr vm                       ; f8001c0f 80800100
	s_endpgm                                                    ; bf810000
	s_code_end                                                  ; bf9f0000
	s_code_end                                                  ; bf9f0000
)";

} // namespace

TEST_CASE("the loops of an ACO listing are its back branches, nested by containment") {
    std::string error;
    const auto listing = read_aco_listing(kNested, &error);
    REQUIRE(listing);
    CHECK(listing->instructions == 9); // s_code_end padding not counted
    REQUIRE(listing->loops.size() == 2);
    CHECK(listing->loops[0].first == 1);
    CHECK(listing->loops[0].last == 6);
    CHECK(listing->loops[0].instructions == 6);
    CHECK(listing->loops[0].depth == 0);
    CHECK(listing->loops[1].first == 3);
    CHECK(listing->loops[1].last == 4);
    CHECK(listing->loops[1].depth == 1);
}

TEST_CASE("the per-pixel estimate multiplies the trip counts down the nest") {
    std::string error;
    const auto listing = read_aco_listing(kNested, &error);
    REQUIRE(listing);
    // Outside: 3 instructions once; outer body less the inner: 4 instructions x 9; the inner
    // body: 2 instructions x 9 x 8.
    CHECK(*weighted_instructions(*listing, {9, 8}) == 3 + 4 * 9 + 2 * 9 * 8);
    CHECK(*weighted_instructions(*listing, {1, 1}) == 9); // once each: the static count
    CHECK_FALSE(weighted_instructions(*listing, {9}));    // a count per loop, or none
}

TEST_CASE("a listing without loops, and listings that are not ACO's, read as such") {
    std::string error;
    const auto flat =
        read_aco_listing("BB0:\n\tv_mov_b32 v0, 1.0 ; 7e0002f2\n\ts_endpgm\n", &error);
    REQUIRE(flat);
    CHECK(flat->instructions == 2);
    CHECK(flat->loops.empty());
    CHECK_FALSE(read_aco_listing("BB0:\n\ts_branch BB7\n", &error));
    CHECK(error.find("BB7") != std::string::npos);
    // Two loops that cross (BB1..branch at 3, BB2..branch at 4) do not nest.
    CHECK_FALSE(read_aco_listing("BB1:\n\ts_nop 0\nBB2:\n\ts_nop 0\n\ts_nop 0\n\ts_branch BB1\n"
                                 "\ts_branch BB2\n",
                                 &error));
    CHECK(error.find("overlap") != std::string::npos);
}
