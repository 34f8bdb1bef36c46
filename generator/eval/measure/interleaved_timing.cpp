#include "watergen/eval/measure/interleaved_timing.h"

#include <algorithm>
#include <string>

namespace watergen {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

namespace {

// splitmix64: a small generator whose sequence is fixed by its seed on every platform (the
// standard distributions are not), so a report's intervals can be reproduced exactly.
struct SplitMix64 {
    uint64_t state;
    uint64_t next() {
        uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
};

// The value at fraction q of sorted `v` (nearest rank).
double quantile(std::vector<double>& v, double q) {
    std::sort(v.begin(), v.end());
    const size_t i = static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5);
    return v[std::min(i, v.size() - 1)];
}

} // namespace

RatioInterval paired_ratio(const std::vector<double>& a, const std::vector<double>& b,
                           uint32_t resamples, uint64_t seed) {
    RatioInterval out;
    if (a.empty() || a.size() != b.size() || resamples == 0) return out;
    std::vector<double> per_round(a.size());
    for (size_t k = 0; k < a.size(); ++k)
        per_round[k] = b[k] > 0 ? a[k] / b[k] : 0.0;
    out.ratio = median(per_round);
    SplitMix64 rng{seed};
    std::vector<double> medians(resamples), sample(per_round.size());
    for (double& m : medians) {
        for (double& s : sample)
            s = per_round[rng.next() % per_round.size()];
        m = median(sample);
    }
    out.lo = quantile(medians, 0.025);
    out.hi = quantile(medians, 0.975);
    return out;
}

std::vector<double> round_medians(const std::vector<double>& draw_ms, uint32_t per_round) {
    std::vector<double> out;
    if (per_round == 0) return out;
    for (size_t i = 0; i + per_round <= draw_ms.size(); i += per_round)
        out.push_back(
            median(std::vector<double>(draw_ms.begin() + static_cast<long>(i),
                                       draw_ms.begin() + static_cast<long>(i + per_round))));
    return out;
}

InterleavedTiming time_interleaved(VulkanRunner& runner, std::vector<RenderJob> jobs,
                                   uint32_t rounds, uint32_t draws_per_round) {
    InterleavedTiming out;
    if (jobs.empty()) return out;
    for (RenderJob& j : jobs)
        j.timed_draws = std::max(draws_per_round, 1u);
    jobs.push_back(jobs.front()); // the A/A copy: its own pipeline, drawn last in each round
    std::vector<RenderResult> results = runner.render_interleaved(jobs, rounds);
    for (size_t i = 0; i < results.size(); ++i)
        if (!results[i].ok) {
            out.error = "job " + std::to_string(i) + ": " + results[i].error;
            return out;
        }
    const uint32_t per_round = std::max(draws_per_round, 1u);
    const std::vector<double> reference = round_medians(results.front().draw_ms, per_round);
    out.aa = paired_ratio(round_medians(results.back().draw_ms, per_round), reference);
    results.pop_back();
    for (const RenderResult& r : results)
        out.ratios.push_back(paired_ratio(round_medians(r.draw_ms, per_round), reference));
    out.results = std::move(results);
    return out;
}

} // namespace watergen
