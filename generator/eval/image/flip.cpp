#include "watergen/eval/image/flip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "watergen/eval/image/image_metrics.h"

namespace watergen {

namespace {

constexpr double kPi = std::numbers::pi;
// Sec. 4.1.3 and 4.3: colour and feature exponents, redistribution breakpoints.
constexpr double kColorExponent = 0.7;   // qc
constexpr double kFeatureExponent = 0.5; // qf
constexpr double kCmaxShare = 0.4;       // pc
constexpr double kErrorAtShare = 0.95;   // pt
// Sec. 4.2: peak-to-trough width of the human edge detector, degrees (2 standard deviations).
constexpr double kFeatureWidthDegrees = 0.082;

// One channel of an image, row-major, row 0 = top.
struct Plane {
    uint32_t width = 0, height = 0;
    std::vector<float> v;
};

// An odd-length 1D kernel; element r of 2r + 1 weighs offset 0.
using Kernel = std::vector<float>;

int clamp_index(int i, int n) {
    return std::clamp(i, 0, n - 1);
}

// Correlates rows with `kx`, then columns with `ky`, replicating border pixels. Because padding
// by replication is itself separable, this equals the 2D correlation with kx(x) ky(y).
Plane filter_separable(const Plane& in, const Kernel& kx, const Kernel& ky) {
    const int w = static_cast<int>(in.width), h = static_cast<int>(in.height);
    const int rx = static_cast<int>(kx.size() / 2), ry = static_cast<int>(ky.size() / 2);
    Plane rows{in.width, in.height, std::vector<float>(in.v.size())};
    for (int y = 0; y < h; ++y) {
        const float* src = &in.v[std::size_t(y) * w];
        for (int x = 0; x < w; ++x) {
            float sum = 0.0f;
            for (int k = -rx; k <= rx; ++k)
                sum += kx[k + rx] * src[clamp_index(x + k, w)];
            rows.v[std::size_t(y) * w + x] = sum;
        }
    }
    Plane out{in.width, in.height, std::vector<float>(in.v.size())};
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            float sum = 0.0f;
            for (int k = -ry; k <= ry; ++k)
                sum += ky[k + ry] * rows.v[std::size_t(clamp_index(y + k, h)) * w + x];
            out.v[std::size_t(y) * w + x] = sum;
        }
    }
    return out;
}

// Sec. 4.1.1: each channel's contrast sensitivity as a sum of Gaussians in the spatial domain,
// S(x) = sum_i a_i sqrt(pi / b_i) exp(-pi^2 |x|^2 / b_i), x in degrees (a2 = 0: one Gaussian).
struct CsfGaussian {
    double a, b;
};
struct CsfChannel {
    std::array<CsfGaussian, 2> terms;
};
constexpr CsfChannel kCsfAchromatic{{{{1.0, 0.0047}, {0.0, 1.0}}}};
constexpr CsfChannel kCsfRedGreen{{{{1.0, 0.0053}, {0.0, 1.0}}}};
constexpr CsfChannel kCsfBlueYellow{{{{34.1, 0.04}, {13.5, 0.025}}}};
constexpr double kCsfWidestB = 0.04;

// One separable term of a channel's kernel: weight * (g x g) with g normalised to sum 1.
struct SeparableTerm {
    double weight;
    Kernel g;
};

// The 2D kernel, normalised to sum 1 as a whole, split into separable Gaussians. Every channel
// uses the radius of the widest Gaussian, 3 standard deviations: ceil(3 sqrt(b / (2 pi^2)) ppd).
std::vector<SeparableTerm> csf_kernel(const CsfChannel& channel, double ppd) {
    const int r = static_cast<int>(std::ceil(3.0 * std::sqrt(kCsfWidestB / (2 * kPi * kPi)) * ppd));
    std::vector<SeparableTerm> terms;
    double total = 0.0;
    for (const CsfGaussian& t : channel.terms) {
        if (t.a == 0.0) continue;
        Kernel g(2 * r + 1);
        double sum = 0.0;
        for (int i = -r; i <= r; ++i) {
            const double x = i / ppd;
            g[i + r] = static_cast<float>(std::exp(-kPi * kPi * x * x / t.b));
            sum += g[i + r];
        }
        for (float& v : g)
            v = static_cast<float>(v / sum);
        // The 2D Gaussian sums to sum^2; its share of the total is a sqrt(pi / b) sum^2.
        const double weight = t.a * std::sqrt(kPi / t.b) * sum * sum;
        total += weight;
        terms.push_back({weight, std::move(g)});
    }
    for (SeparableTerm& t : terms)
        t.weight /= total;
    return terms;
}

Plane filter_csf(const Plane& in, const CsfChannel& channel, double ppd) {
    Plane out{in.width, in.height, std::vector<float>(in.v.size(), 0.0f)};
    for (const SeparableTerm& t : csf_kernel(channel, ppd)) {
        const Plane part = filter_separable(in, t.g, t.g);
        for (std::size_t i = 0; i < out.v.size(); ++i)
            out.v[i] += static_cast<float>(t.weight) * part.v[i];
    }
    return out;
}

// YCxCz (Zhang and Wandell's linearised CIELAB): Y = 116 y - 16, Cx = 500 (x - y),
// Cz = 200 (y - z) with x, y, z = X / Xn, Y / Yn, Z / Zn.
struct Opponent {
    Plane y, cx, cz;
};

Opponent to_opponent(const ImageRGBA8& image) {
    static const std::array<double, 256> decode = [] {
        std::array<double, 256> t{};
        for (int i = 0; i < 256; ++i)
            t[i] = srgb_to_linear(i / 255.0);
        return t;
    }();
    const XYZ white = srgb_white_xyz();
    const std::size_t n = image.pixel_count();
    Opponent o{{image.width, image.height, std::vector<float>(n)},
               {image.width, image.height, {}},
               {image.width, image.height, {}}};
    o.cx.v.resize(n);
    o.cz.v.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const uint8_t* px = &image.rgba[i * 4];
        const XYZ c = linear_srgb_to_xyz(decode[px[0]], decode[px[1]], decode[px[2]]);
        const double x = c.X / white.X, y = c.Y / white.Y, z = c.Z / white.Z;
        o.y.v[i] = static_cast<float>(116.0 * y - 16.0);
        o.cx.v[i] = static_cast<float>(500.0 * (x - y));
        o.cz.v[i] = static_cast<float>(200.0 * (y - z));
    }
    return o;
}

// The inverse of linear_srgb_to_xyz's matrix (columns are the images of the primaries).
std::array<std::array<double, 3>, 3> xyz_to_linear_srgb_matrix() {
    const XYZ r = linear_srgb_to_xyz(1, 0, 0), g = linear_srgb_to_xyz(0, 1, 0),
              b = linear_srgb_to_xyz(0, 0, 1);
    const double m[3][3] = {{r.X, g.X, b.X}, {r.Y, g.Y, b.Y}, {r.Z, g.Z, b.Z}};
    std::array<std::array<double, 3>, 3> inv{};
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            // Adjugate: cofactor of (j, i) over the determinant.
            const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
            inv[i][j] = (m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]) / det;
        }
    }
    return inv;
}

// Hunt adjustment (sec. 4.1.2): chroma shrinks with lightness, a' = 0.01 L a, b' = 0.01 L b.
Lab hunt_adjusted(Lab c) {
    return Lab{c.L, 0.01 * c.L * c.a, 0.01 * c.L * c.b};
}

double hyab(Lab p, Lab q) {
    return std::abs(p.L - q.L) + std::hypot(p.a - q.a, p.b - q.b);
}

// Filters each opponent channel, returns to linear RGB clamped to the unit cube, then to
// Hunt-adjusted CIELAB.
std::vector<Lab> filtered_hunt_lab(const Opponent& o, double ppd) {
    const Plane y = filter_csf(o.y, kCsfAchromatic, ppd);
    const Plane cx = filter_csf(o.cx, kCsfRedGreen, ppd);
    const Plane cz = filter_csf(o.cz, kCsfBlueYellow, ppd);
    static const auto inv = xyz_to_linear_srgb_matrix();
    const XYZ white = srgb_white_xyz();
    std::vector<Lab> out(y.v.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        const double yy = (y.v[i] + 16.0) / 116.0;
        const double xyz[3] = {(yy + cx.v[i] / 500.0) * white.X, yy * white.Y,
                               (yy - cz.v[i] / 200.0) * white.Z};
        double rgb[3];
        for (int c = 0; c < 3; ++c)
            rgb[c] =
                std::clamp(inv[c][0] * xyz[0] + inv[c][1] * xyz[1] + inv[c][2] * xyz[2], 0.0, 1.0);
        out[i] = hunt_adjusted(linear_srgb_to_lab(rgb[0], rgb[1], rgb[2]));
    }
    return out;
}

// Sec. 4.1.3: HyAB^qc mapped to [0, 1], the first pc of [0, cmax] onto [0, pt].
double redistributed_color_error(double hyab_distance, double cmax) {
    const double e = std::pow(hyab_distance, kColorExponent);
    const double knee = kCmaxShare * cmax;
    if (e < knee) return kErrorAtShare / knee * e;
    return std::min(1.0, kErrorAtShare + (e - knee) / (cmax - knee) * (1.0 - kErrorAtShare));
}

// Sec. 4.2: the derivative kernels along one axis, normalised so that positive weights sum to 1
// and negative ones to -1, and the Gaussian across it normalised to sum 1 (the 2D kernel's
// normalisation factors into these two because the sign depends on one axis only).
struct FeatureKernels {
    Kernel edge, point, across;
};

FeatureKernels feature_kernels(double ppd) {
    const double sd = 0.5 * kFeatureWidthDegrees * ppd;
    const int r = static_cast<int>(std::ceil(3.0 * sd));
    FeatureKernels k{Kernel(2 * r + 1), Kernel(2 * r + 1), Kernel(2 * r + 1)};
    std::vector<double> edge(2 * r + 1), point(2 * r + 1), gauss(2 * r + 1);
    for (int i = -r; i <= r; ++i) {
        const double g = std::exp(-double(i) * i / (2.0 * sd * sd));
        gauss[i + r] = g;
        edge[i + r] = -i * g;
        point[i + r] = (double(i) * i / (sd * sd) - 1.0) * g;
    }
    auto normalise = [](const std::vector<double>& in, Kernel& out) {
        double pos = 0.0, neg = 0.0;
        for (double v : in)
            (v > 0 ? pos : neg) += v;
        for (std::size_t i = 0; i < in.size(); ++i)
            out[i] = static_cast<float>(in[i] > 0 ? in[i] / pos : (neg < 0 ? in[i] / -neg : 0.0));
    };
    normalise(edge, k.edge);
    normalise(point, k.point);
    double sum = 0.0;
    for (double g : gauss)
        sum += g;
    for (std::size_t i = 0; i < gauss.size(); ++i)
        k.across[i] = static_cast<float>(gauss[i] / sum);
    return k;
}

// Edge and point magnitudes: the norms of the x and y responses.
struct Features {
    Plane edge, point;
};

Features detect_features(const Plane& achromatic, const FeatureKernels& k) {
    auto magnitude = [&](const Kernel& d) {
        Plane gx = filter_separable(achromatic, d, k.across);
        const Plane gy = filter_separable(achromatic, k.across, d);
        for (std::size_t i = 0; i < gx.v.size(); ++i)
            gx.v[i] = std::hypot(gx.v[i], gy.v[i]);
        return gx;
    };
    return Features{magnitude(k.edge), magnitude(k.point)};
}

// Y / Yn in [0, 1] from YCxCz's Y.
Plane normalised_achromatic(const Plane& y) {
    Plane out = y;
    for (float& v : out.v)
        v = (v + 16.0f) / 116.0f;
    return out;
}

void fill_statistics(FlipMap& m) {
    std::vector<double> values(m.values.begin(), m.values.end());
    double sum = 0.0;
    for (double v : values) {
        sum += v;
        m.max = std::max(m.max, v);
    }
    m.mean = sum / double(values.size());
    m.p50 = nearest_rank_percentile(values, 50);
    m.p95 = nearest_rank_percentile(values, 95);
    m.p99 = nearest_rank_percentile(values, 99);
}

std::string input_error(const ImageRGBA8& reference, const ImageRGBA8& test) {
    if (!reference.well_formed() || !test.well_formed())
        return "FLIP: malformed image (pixel bytes do not match width x height x 4)";
    if (reference.width != test.width || reference.height != test.height)
        return fmt::format("FLIP: image sizes differ: reference is {}x{}, test is {}x{}",
                           reference.width, reference.height, test.width, test.height);
    if (reference.pixel_count() == 0) return "FLIP: empty images";
    return {};
}

} // namespace

double flip_cmax() {
    const Lab green = hunt_adjusted(linear_srgb_to_lab(0, 1, 0));
    const Lab blue = hunt_adjusted(linear_srgb_to_lab(0, 0, 1));
    return std::pow(hyab(green, blue), kColorExponent);
}

FlipMap flip_srgb8(const ImageRGBA8& reference, const ImageRGBA8& test, double ppd) {
    FlipMap m;
    if (m.error = input_error(reference, test); !m.error.empty()) return m;
    if (!(ppd > 0.0) || !std::isfinite(ppd)) {
        m.error = fmt::format("FLIP: pixels per degree must be positive, got {}", ppd);
        return m;
    }
    m.width = reference.width;
    m.height = reference.height;
    const Opponent ref = to_opponent(reference), tst = to_opponent(test);
    const std::vector<Lab> ref_lab = filtered_hunt_lab(ref, ppd);
    const std::vector<Lab> tst_lab = filtered_hunt_lab(tst, ppd);
    const FeatureKernels kernels = feature_kernels(ppd);
    const Features ref_f = detect_features(normalised_achromatic(ref.y), kernels);
    const Features tst_f = detect_features(normalised_achromatic(tst.y), kernels);
    const double cmax = flip_cmax();

    m.values.resize(reference.pixel_count());
    for (std::size_t i = 0; i < m.values.size(); ++i) {
        const double color = redistributed_color_error(hyab(ref_lab[i], tst_lab[i]), cmax);
        const double feature_gap = std::max(std::abs(ref_f.edge.v[i] - tst_f.edge.v[i]),
                                            std::abs(ref_f.point.v[i] - tst_f.point.v[i]));
        const double feature =
            std::min(1.0, std::pow(feature_gap / std::numbers::sqrt2, kFeatureExponent));
        m.values[i] = static_cast<float>(std::pow(color, 1.0 - feature));
    }
    fill_statistics(m);
    return m;
}

FlipMap flip_linear(const ImageRGBA32F& reference, const ImageRGBA32F& test, float exposure,
                    double ppd) {
    if (!reference.well_formed() || !test.well_formed()) {
        FlipMap m;
        m.error = "FLIP: malformed image (floats do not match width x height x 4)";
        return m;
    }
    const ImageRGBA8 ref8{reference.width, reference.height,
                          tone_map_to_srgb8(reference, exposure)};
    const ImageRGBA8 test8{test.width, test.height, tone_map_to_srgb8(test, exposure)};
    return flip_srgb8(ref8, test8, ppd);
}

} // namespace watergen
