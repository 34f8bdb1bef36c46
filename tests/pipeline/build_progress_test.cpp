// The progress line of a long build (build_progress.h): its rate, the time left at that rate,
// and the duration format; the peak memory the summary line reports.
#include <catch2/catch.hpp>

#include <vector>

#include "watergen/pipeline/jobs/build_progress.h"

using namespace watergen;

TEST_CASE("the progress line gives the rate and the time left at that rate", "[unit]") {
    BuildProgress p;
    p.done = 120;
    p.total = 1764;
    p.cached = 3;
    // 120 jobs in 7.2 s: 16.7 per second; 1644 left take 98.6 s.
    CHECK(progress_text(p, 7.2, "variants") ==
          "[120/1764] 16.7 variants/s, 1 min 39 s left, 3 cached, 0 failed");
    p.done = 0;
    CHECK(progress_text(p, 0.0, "shaders") == "[0/1764] 0.0 shaders/s, - left, 3 cached, 0 failed");
}

TEST_CASE("durations read as seconds, minutes and hours", "[unit]") {
    CHECK(duration_text(0.4) == "0 s");
    CHECK(duration_text(42) == "42 s");
    CHECK(duration_text(99) == "1 min 39 s");
    CHECK(duration_text(7530) == "2 h 5 min");
}

TEST_CASE("the peak memory grows with what the process touched", "[unit]") {
    const uint64_t before = peak_resident_bytes();
    CHECK(before > 1000000);              // a test binary holds more than a megabyte
    std::vector<char> block(64 << 20, 1); // 64 MiB, written
    CHECK(peak_resident_bytes() >= before);
    CHECK(peak_resident_bytes() >= uint64_t(64) << 20);
    CHECK(block[12345] == 1);
}
