// Host values in double (host_values.h).
#include "watergen/runtime/host_values.h"

#include <array>
#include <cmath>

namespace watergen {

namespace {

// A double-double: hi + lo, |lo| <= ulp(hi) / 2 (Dekker; Shewchuk's two-sum).
struct Double2 {
    double hi = 0, lo = 0;
};

Double2 two_sum(double a, double b) {
    const double s = a + b, bb = s - a;
    return {s, (a - (s - bb)) + (b - bb)};
}

Double2 two_product(double a, double b) {
    const double p = a * b;
    return {p, std::fma(a, b, -p)};
}

Double2 add(Double2 x, Double2 y) {
    const Double2 s = two_sum(x.hi, y.hi);
    return two_sum(s.hi, s.lo + x.lo + y.lo);
}

Double2 times(Double2 x, double b) {
    Double2 p = two_product(x.hi, b);
    return two_sum(p.hi, p.lo + x.lo * b);
}

Double2 negate(Double2 x) {
    return {-x.hi, -x.lo};
}

// 2 pi as three doubles (hex of the binary expansion): k times each part is exact for the
// first two (two_product), so the reduced phase keeps about 1e-16 of the unreduced one for
// every |k| < 2^53.
constexpr double kTwoPi0 = 0x1.921fb54442d18p+2;
constexpr double kTwoPi1 = 0x1.1a62633145c07p-52;
constexpr double kTwoPi2 = -0x1.f1976b7ed8fbcp-108;
constexpr double kPi = kTwoPi0 / 2;

double reduce_two_pi(Double2 x) {
    const double k = std::nearbyint(x.hi / kTwoPi0);
    Double2 r = add(x, negate(two_product(k, kTwoPi0)));
    r = add(r, negate(two_product(k, kTwoPi1)));
    double out = r.hi + (r.lo - k * kTwoPi2);
    // nearbyint leaves |out| <= pi plus rounding; the half-open range is the promise.
    if (out >= kPi) out -= kTwoPi0;
    if (out < -kPi) out += kTwoPi0;
    return out;
}

double reduce_one(Double2 x) {
    const double k = std::floor(x.hi);
    const Double2 r = add(x, {-k, 0.0});
    double out = r.hi + r.lo;
    if (out >= 1.0) out -= 1.0;
    if (out < 0.0) out += 1.0;
    return out >= 1.0 ? 0.0 : out;
}

struct Names {
    HostRule rule;
    const char* name;
    bool computed;
    size_t inputs;
};

constexpr std::array<Names, 8> kRules = {{
    {HostRule::Given, "given", false, 0},
    {HostRule::FramePoint, "frame_point", false, 0},
    {HostRule::FramePointXZ, "frame_point_xz", false, 0},
    {HostRule::FrameWorldToClip, "frame_world_to_clip", false, 2},
    {HostRule::FrameClipToWorld, "frame_clip_to_world", false, 1},
    {HostRule::WavePhases, "wave_phases", true, 5},
    {HostRule::ScrollOffset, "scroll_offset", true, 3},
    {HostRule::TileOffset, "tile_offset", true, 1},
}};

const Names& row(HostRule rule) {
    for (const Names& n : kRules)
        if (n.rule == rule) return n;
    return kRules[0];
}

} // namespace

const char* host_rule_name(HostRule rule) {
    return row(rule).name;
}

std::optional<HostRule> host_rule_from_name(std::string_view name) {
    for (const Names& n : kRules)
        if (name == n.name) return n.rule;
    return std::nullopt;
}

bool host_rule_computed(HostRule rule) {
    return row(rule).computed;
}

size_t host_rule_inputs(HostRule rule) {
    return row(rule).inputs;
}

FrameCentre frame_centre_of(double eye_x, double eye_z) {
    if (!std::isfinite(eye_x) || !std::isfinite(eye_z)) return {};
    return {(std::floor(eye_x / kFrameCell) + 0.5) * kFrameCell,
            (std::floor(eye_z / kFrameCell) + 0.5) * kFrameCell};
}

double wave_phase_offset(double frequency, double dx, double dz, double speed, double time,
                         const Frame& frame) {
    const Double2 along =
        add(add(two_product(dx, frame.centre.x), two_product(dz, frame.centre.z)),
            add(two_product(dx, frame.origin.x), two_product(dz, frame.origin.z)));
    return reduce_two_pi(add(times(along, frequency), two_product(speed, time)));
}

double scroll_offset(double origin, double x, double scale, double rate, double time) {
    return reduce_one(
        add(add(two_product(origin, scale), two_product(x, scale)), two_product(rate, time)));
}

std::optional<std::vector<double>> host_value(const HostValue& h, const std::vector<double>& own,
                                              const GivenValues& given, const Frame& frame,
                                              std::string* error) {
    const FrameCentre& c = frame.centre;
    const size_t wanted = host_rule_inputs(h.rule);
    if (h.inputs.size() != wanted) {
        *error = std::string("host rule ") + host_rule_name(h.rule) + " reads " +
                 std::to_string(wanted) + " inputs; " + std::to_string(h.inputs.size()) +
                 " are named";
        return std::nullopt;
    }
    std::vector<const std::vector<double>*> in;
    for (const std::string& name : h.inputs) {
        const std::vector<double>* v = given(name);
        if (!v) {
            *error = std::string("host rule ") + host_rule_name(h.rule) + " reads '" + name +
                     "', which has no value";
            return std::nullopt;
        }
        in.push_back(v);
    }
    auto sized = [&](size_t k, size_t n) {
        if (in[k]->size() == n) return true;
        *error = std::string("host rule ") + host_rule_name(h.rule) + ": '" + h.inputs[k] +
                 "' has " + std::to_string(in[k]->size()) + " values; " + std::to_string(n) +
                 " expected";
        return false;
    };
    std::vector<double> out = own;
    switch (h.rule) {
    case HostRule::Given:
        return out;
    case HostRule::FramePoint:
        if (out.size() != 3) break;
        out[0] -= c.x;
        out[2] -= c.z;
        return out;
    case HostRule::FramePointXZ:
        if (out.size() < 2) break;
        out[0] -= c.x;
        out[1] -= c.z;
        return out;
    case HostRule::FrameWorldToClip:
        // M T(c) for a point relative to c: column 3 gains M (c.x, 0, c.z, 0).
        if (out.size() != 4 || !sized(0, 4) || !sized(1, 4)) break;
        for (size_t k = 0; k < 4; ++k)
            out[k] += (*in[0])[k] * c.x + (*in[1])[k] * c.z;
        return out;
    case HostRule::FrameClipToWorld:
        // T(-c) M: the homogeneous point (x, y, z, w) becomes (x - c.x w, y, z - c.z w, w).
        if (out.size() != 4 || !sized(0, 1)) break;
        if ((*in[0])[0] > 0.5) return out;
        out[0] -= c.x * out[3];
        out[2] -= c.z * out[3];
        return out;
    case HostRule::WavePhases: {
        const size_t n = own.size();
        if (!sized(0, 1) || !sized(1, 1) || !sized(2, 1) || !sized(3, n) || !sized(4, 2 * n))
            return std::nullopt;
        const double t = (*in[0])[0], gain = (*in[2])[0];
        // f_i in the order the shader's loop multiplies it (wave_families.cpp, sum_over_waves),
        // so the CPU evaluator's double f_i is this one.
        double f = (*in[1])[0];
        for (size_t i = 0; i < n; ++i) {
            out[i] =
                wave_phase_offset(f, (*in[4])[2 * i], (*in[4])[2 * i + 1], (*in[3])[i], t, frame);
            f *= gain;
        }
        return out;
    }
    case HostRule::ScrollOffset: {
        const size_t n = in[1]->size();
        if (!sized(0, 1) || !sized(2, 2 * n) || own.size() != 2 * n) break;
        const double t = (*in[0])[0];
        for (size_t k = 0; k < n; ++k) {
            out[2 * k] = scroll_offset(frame.origin.x, c.x, (*in[1])[k], (*in[2])[2 * k], t);
            out[2 * k + 1] =
                scroll_offset(frame.origin.z, c.z, (*in[1])[k], (*in[2])[2 * k + 1], t);
        }
        return out;
    }
    case HostRule::TileOffset: {
        if (!sized(0, 1) || own.size() != 2 || !((*in[0])[0] > 0)) break;
        const double size = (*in[0])[0];
        // fmod is exact; the sum of two remainders rounds once, the quotient once.
        auto tile = [size](double origin, double x) {
            double r = std::fmod(std::fmod(origin, size) + std::fmod(x, size), size);
            if (r < 0) r += size;
            const double u = r / size;
            return u >= 1.0 ? 0.0 : u;
        };
        out = {tile(frame.origin.x, c.x), tile(frame.origin.z, c.z)};
        return out;
    }
    }
    *error = std::string("host rule ") + host_rule_name(h.rule) + " cannot make " +
             std::to_string(own.size()) + " values";
    return std::nullopt;
}

} // namespace watergen
