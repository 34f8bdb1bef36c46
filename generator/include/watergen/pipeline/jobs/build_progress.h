// What a long build says while it runs and when it ends: jobs done, jobs per second since the
// start, the time left at that rate, and the process's peak memory.
#pragma once

#include <cstdint>
#include <string>

#include "watergen/pipeline/jobs/parallel_build.h"

namespace watergen {

// "[120/1764] 16.6 variants/s, 1 min 39 s left, 3 cached, 0 failed": the rate over `seconds`
// since the build started, the time left at that rate ("- left" before the first job is done);
// `jobs` names what a job is (variants in a permutations build, shaders in the others).
std::string progress_text(const BuildProgress& p, double seconds, const std::string& jobs);

// "1 min 39 s", "42 s", "2 h 5 min": a duration for people.
std::string duration_text(double seconds);

// The peak resident set of this process so far, in bytes (getrusage).
uint64_t peak_resident_bytes();

} // namespace watergen
