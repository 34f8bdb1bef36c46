#include "watergen/eval/image/agreement.h"

#include <algorithm>
#include <cmath>

namespace watergen {

Agreement check_agreement(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                          const std::vector<float>& bound, double tolerance) {
    Agreement a;
    a.tolerance = tolerance;
    if (test.width != reference.width || test.height != reference.height) return a;
    const size_t pixels = size_t(test.width) * test.height;
    double worst_excess = -INFINITY, worst_plain = -1;
    PixelLocation plain;
    double plain_bound = 0;
    for (size_t p = 0; p < pixels; ++p) {
        double d = 0;
        bool finite = true;
        for (size_t c = 0; c < 3; ++c) {
            const double t = test.rgba[p * 4 + c], r = reference.rgba[p * 4 + c];
            finite = finite && std::isfinite(t) && std::isfinite(r);
            d = std::max(d, std::fabs(t - r));
        }
        if (!finite) continue;
        ++a.compared;
        const double b = p < bound.size() ? double(bound[p]) : 0.0;
        a.max_bound = std::max(a.max_bound, b);
        const PixelLocation at{uint32_t(p % test.width), uint32_t(p / test.width)};
        if (d > worst_plain) {
            worst_plain = d;
            plain = at;
            plain_bound = b;
        }
        if (d <= tolerance) continue;
        ++a.over_tolerance;
        const double excess = d - (tolerance + b);
        if (excess > 0) ++a.over_bound;
        if (excess > 0 && excess > worst_excess) {
            worst_excess = excess;
            a.worst = at;
            a.worst_difference = d;
            a.worst_bound = b;
        }
    }
    if (a.over_bound == 0) {
        a.worst = plain;
        a.worst_difference = std::max(worst_plain, 0.0);
        a.worst_bound = plain_bound;
    }
    return a;
}

} // namespace watergen
