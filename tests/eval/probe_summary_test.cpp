// summarize_probe on hand-made runs: a GPU result that is NaN or Inf where the reference is
// finite is counted, and the reference is the CPU float result, or the CPU half result for a
// strict-half run (its GPU side computes what the half model computes).
#include <catch2/catch.hpp>

#include <cmath>

#include "watergen/eval/probe/probe_table.h"

using namespace watergen;

namespace {

ProbeRun two_tuple_run(bool strict_half) {
    ProbeRun run;
    run.layout.output_stride = 1;
    run.tuples = 2;
    run.strict_half = strict_half;
    run.gpu = {0.25, NAN};
    run.cpu_double = {0.25, 1.0};
    run.cpu_float = {0.25, 1.0};
    run.cpu_half = {0.25 + 0x1p-12, INFINITY}; // one binary16 step above 0.25; overflowed
    return run;
}

} // namespace

TEST_CASE("a_gpu_nan_where_the_cpu_float_is_finite_breaks_the_node", "[probe]") {
    const ProbeSummary s = summarize_probe(two_tuple_run(false));
    CHECK(s.gpu.nan == 1);
    CHECK(s.gpu_only_non_finite == 1);
    CHECK(s.first_gpu_only_tuple == 1);
    CHECK_FALSE(s.gpu_stable());
    CHECK(s.gpu_vs_cpu_half.values == 0); // not a strict-half run
}

TEST_CASE("a_strict_half_run_is_held_against_the_cpu_half_result", "[probe][half]") {
    const ProbeSummary s = summarize_probe(two_tuple_run(true));
    CHECK(s.gpu_only_non_finite == 0); // the half model overflowed too
    CHECK(s.gpu_stable());
    REQUIRE(s.gpu_vs_cpu_half.values == 1);
    CHECK(s.gpu_vs_cpu_half.max_ulps == 1);
    CHECK(s.gpu_vs_cpu_half.equal == 0);
    CHECK(s.gpu_vs_cpu_half.within_1 == 1);
    CHECK(s.max_gpu_vs_cpu_half == 0x1p-12);
}
