// Draw times of several variants that can be compared on a busy, shared machine: the variants
// are drawn interleaved (A B C A B C ...), so a slow spell of the machine falls on all of them,
// each ratio to the reference is taken round by round and given a 95% bootstrap interval, and
// the reference is timed against a second pipeline of itself (A/A): if that does not come out
// at 1.00 within +-3%, the machine is too noisy for the ratios to mean anything, and the
// result says so.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "watergen/runner/vulkan_runner.h"

namespace watergen {

// The median of timed repetitions (0 for none), as every bench reports them.
double median(std::vector<double> v);

struct RatioInterval {
    double ratio = 0;      // median over rounds of (this round's time / the reference's)
    double lo = 0, hi = 0; // its 95% bootstrap interval
    // True when the whole interval lies within 1 +- tolerance.
    bool within(double tolerance) const { return lo >= 1.0 - tolerance && hi <= 1.0 + tolerance; }
};

// The ratio a/b of paired samples (a[k] and b[k] measured in the same round k): the median of
// a[k]/b[k], and the 2.5th and 97.5th percentiles of that median over `resamples` resamplings
// of the rounds with replacement (percentile bootstrap). Seeded: the same samples always give
// the same interval. Empty or unequal inputs give all zeros.
RatioInterval paired_ratio(const std::vector<double>& a, const std::vector<double>& b,
                           uint32_t resamples = 2000, uint64_t seed = 0x9e3779b97f4a7c15ull);

// One value per round from a job's draw_ms (render_interleaved): the median of the round's
// `per_round` draws.
std::vector<double> round_medians(const std::vector<double>& draw_ms, uint32_t per_round);

// The A/A check's tolerance: the reference against itself must come out within +-3%.
constexpr double kAATolerance = 0.03;

struct InterleavedTiming {
    std::vector<RenderResult> results; // per job, in the order given (images read back too)
    std::vector<RatioInterval> ratios; // per job: its steady draw time / job 0's
    RatioInterval aa;                  // job 0 against a second pipeline of job 0
    bool trustworthy() const { return aa.within(kAATolerance); }
    std::string error; // the first job that failed, "" when all ran
    bool ok() const { return error.empty(); }
};

// What:   renders `jobs` (job 0 is the reference) plus a second copy of job 0 with
//         VulkanRunner::render_interleaved: `rounds` rounds of `draws_per_round` draws of each
//         job in turn, the first (JIT) draw of each excluded; then every job's ratio to job 0
//         and the A/A ratio, paired by round.
// Cost:   (jobs + 1) pipelines, (jobs + 1) * (1 + rounds * draws_per_round) draws.
InterleavedTiming time_interleaved(VulkanRunner& runner, std::vector<RenderJob> jobs,
                                   uint32_t rounds, uint32_t draws_per_round);

} // namespace watergen
