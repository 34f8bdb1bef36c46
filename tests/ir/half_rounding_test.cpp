#include <catch2/catch.hpp>

#include <cmath>

#include "watergen/ir/cpu/cpu_evaluator.h"

using namespace watergen;

// binary16: 10 fraction bits, exponent -14..15, subnormal spacing 2^-24, max 65504.
TEST_CASE("half_rounding_matches_binary16", "[half]") {
    CHECK(round_to_half(1.0) == 1.0);
    CHECK(round_to_half(1.0 + std::ldexp(1.0, -11)) == 1.0); // tie -> even
    CHECK(round_to_half(1.0 + 3 * std::ldexp(1.0, -11)) ==
          1.0 + std::ldexp(1.0, -9)); // tie -> even (up)
    CHECK(round_to_half(0.1) == 0.0999755859375);
    CHECK(round_to_half(65504.0) == 65504.0);
    CHECK(round_to_half(65519.0) == 65504.0);
    CHECK(std::isinf(round_to_half(65520.0)));
    CHECK(round_to_half(std::ldexp(1.0, -24)) == std::ldexp(1.0, -24));
    CHECK(round_to_half(std::ldexp(1.0, -26)) == 0.0);
    CHECK(round_to_half(-std::ldexp(3.0, -25)) == -std::ldexp(1.0, -23));
    CHECK(round_to_half(1e5) == INFINITY);
    CHECK(std::isnan(round_to_half(NAN)));
}

TEST_CASE("float_rounding_is_binary32", "[half]") {
    CHECK(round_to(0.1, EvalPrecision::Float) == static_cast<double>(0.1f));
    CHECK(round_to(0.1, EvalPrecision::Double) == 0.1);
}

TEST_CASE("half_ulp_distance_counts_binary16_steps", "[half]") {
    CHECK(half_ulp_distance(1.0, 1.0) == 0);
    CHECK(half_ulp_distance(0.0, -0.0) == 0);
    CHECK(half_ulp_distance(1.0, 1.0 + 0x1p-10) == 1);         // spacing 2^-10 in [1, 2)
    CHECK(half_ulp_distance(1.0, 1.0 - 0x1p-11) == 1);         // spacing 2^-11 in [0.5, 1)
    CHECK(half_ulp_distance(2048.0, 2050.0) == 1);             // spacing 2 in [2048, 4096)
    CHECK(half_ulp_distance(0x1p-24, -0x1p-24) == 2);          // the two smallest subnormals
    CHECK(half_ulp_distance(0x1p-14, 0x1p-14 - 0x1p-24) == 1); // normal to largest subnormal
    CHECK(half_ulp_distance(65504.0, INFINITY) == 1);
    CHECK(half_ulp_distance(-1.0, 1.0) == 2 * 15 * 1024); // 15 binades of 1024 below 1
    CHECK(half_ulp_distance(NAN, 1.0) == -1);
}

TEST_CASE("half_rounding_toward_zero_truncates", "[half]") {
    CHECK(round_to_half_toward_zero(1.0 + 0x1p-11) == 1.0);        // nearest would tie to 1 too
    CHECK(round_to_half_toward_zero(1.0 + 0x1p-10 * 0.75) == 1.0); // nearest: 1 + 2^-10
    CHECK(round_to_half_toward_zero(-(1.0 + 0x1p-10 * 0.75)) == -1.0);
    CHECK(round_to_half_toward_zero(2.0 - 0x1p-13) == 2.0 - 0x1p-10); // below a power of two
    CHECK(round_to_half_toward_zero(0.712686658) == 1459.0 / 2048);   // a sample lavapipe gave
    CHECK(round_to_half_toward_zero(70000.0) == 65504.0);
    CHECK(round_to_half_toward_zero(0.75) == 0.75);
    CHECK(std::isinf(round_to_half_toward_zero(INFINITY)));
}
