#include "watergen/pipeline/jobs/build_progress.h"

#include <algorithm>
#include <cmath>

#include <sys/resource.h>

#include <fmt/format.h>

namespace watergen {

std::string duration_text(double seconds) {
    const long s = std::lround(std::max(seconds, 0.0));
    if (s < 60) return fmt::format("{} s", s);
    if (s < 3600) return fmt::format("{} min {} s", s / 60, s % 60);
    return fmt::format("{} h {} min", s / 3600, (s % 3600) / 60);
}

std::string progress_text(const BuildProgress& p, double seconds, const std::string& jobs) {
    const double rate = seconds > 0 ? double(p.done) / seconds : 0;
    const std::string left =
        rate > 0 ? duration_text(double(p.total - p.done) / rate) + " left" : "- left";
    return fmt::format("[{}/{}] {:.1f} {}/s, {}, {} cached, {} failed", p.done, p.total, rate, jobs,
                       left, p.cached, p.failed);
}

uint64_t peak_resident_bytes() {
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
    return uint64_t(usage.ru_maxrss) * 1024; // kilobytes on Linux
}

} // namespace watergen
