#include "watergen/eval/image/image_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <fmt/core.h>

namespace watergen {

namespace {

constexpr double kPi = std::numbers::pi;
double deg(double rad) {
    return rad * (180.0 / kPi);
}
double rad(double deg) {
    return deg * (kPi / 180.0);
}
double pow7(double x) {
    const double x2 = x * x;
    return x2 * x2 * x2 * x;
}

bool finite_rgb(const float* px) {
    return std::isfinite(px[0]) && std::isfinite(px[1]) && std::isfinite(px[2]);
}

std::string shape_error(const char* which, const ImageRGBA32F& image) {
    if (!image.well_formed()) {
        return fmt::format("{} image is malformed: {}x{} needs {} floats, has {}", which,
                           image.width, image.height, image.pixel_count() * 4, image.rgba.size());
    }
    if (image.pixel_count() == 0) {
        return fmt::format("{} image is empty ({}x{})", which, image.width, image.height);
    }
    return {};
}

} // namespace

double ciede2000(Lab x, Lab y) {
    // Equation numbers are those of Sharma, Wu, Dalal (2005).
    constexpr double k25_7 = 6103515625.0;  // 25^7
    const double c1 = std::hypot(x.a, x.b); // (2)
    const double c2 = std::hypot(y.a, y.b);
    const double c_bar = 0.5 * (c1 + c2);                                          // (3)
    const double g = 0.5 * (1.0 - std::sqrt(pow7(c_bar) / (pow7(c_bar) + k25_7))); // (4)
    const double a1p = (1.0 + g) * x.a;                                            // (5)
    const double a2p = (1.0 + g) * y.a;
    const double c1p = std::hypot(a1p, x.b); // (6)
    const double c2p = std::hypot(a2p, y.b);
    // (7): hue angle in degrees, [0, 360); 0 when a' = b = 0 (explicit, so -0.0 cannot give 180).
    auto hue = [](double ap, double b) {
        if (ap == 0.0 && b == 0.0) return 0.0;
        const double h = deg(std::atan2(b, ap));
        return h < 0.0 ? h + 360.0 : h;
    };
    const double h1p = hue(a1p, x.b);
    const double h2p = hue(a2p, y.b);

    const double dlp = y.L - x.L; // (8)
    const double dcp = c2p - c1p; // (9)
    const bool achromatic = c1p * c2p == 0.0;
    double dhp = 0.0; // (10)
    if (!achromatic) {
        dhp = h2p - h1p;
        if (dhp > 180.0)
            dhp -= 360.0;
        else if (dhp < -180.0)
            dhp += 360.0;
    }
    const double dhp_big = 2.0 * std::sqrt(c1p * c2p) * std::sin(rad(dhp) / 2.0); // (11)

    const double lp_bar = 0.5 * (x.L + y.L); // (12)
    const double cp_bar = 0.5 * (c1p + c2p); // (13)
    double hp_bar = h1p + h2p;               // (14)
    if (!achromatic) {
        if (std::abs(h1p - h2p) <= 180.0)
            hp_bar *= 0.5;
        else if (hp_bar < 360.0)
            hp_bar = 0.5 * (hp_bar + 360.0);
        else
            hp_bar = 0.5 * (hp_bar - 360.0);
    }
    const double t = 1.0 - 0.17 * std::cos(rad(hp_bar - 30.0)) +
                     0.24 * std::cos(rad(2.0 * hp_bar)) + 0.32 * std::cos(rad(3.0 * hp_bar + 6.0)) -
                     0.20 * std::cos(rad(4.0 * hp_bar - 63.0));                      // (15)
    const double d_theta = 30.0 * std::exp(-std::pow((hp_bar - 275.0) / 25.0, 2.0)); // (16)
    const double rc = 2.0 * std::sqrt(pow7(cp_bar) / (pow7(cp_bar) + k25_7));        // (17)
    const double l50 = (lp_bar - 50.0) * (lp_bar - 50.0);
    const double sl = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50); // (18)
    const double sc = 1.0 + 0.045 * cp_bar;                      // (19)
    const double sh = 1.0 + 0.015 * cp_bar * t;                  // (20)
    const double rt = -std::sin(rad(2.0 * d_theta)) * rc;        // (21)

    const double tl = dlp / sl, tc = dcp / sc, th = dhp_big / sh; // kL = kC = kH = 1
    return std::sqrt(tl * tl + tc * tc + th * th + rt * tc * th); // (22)
}

XYZ linear_srgb_to_xyz(double r, double g, double b) {
    // IEC 61966-2-1 matrix; the white point is its row sums (D65).
    return XYZ{0.4124 * r + 0.3576 * g + 0.1805 * b, 0.2126 * r + 0.7152 * g + 0.0722 * b,
               0.0193 * r + 0.1192 * g + 0.9505 * b};
}

XYZ srgb_white_xyz() {
    return XYZ{0.4124 + 0.3576 + 0.1805, 1.0, 0.0193 + 0.1192 + 0.9505};
}

Lab linear_srgb_to_lab(double r, double g, double b) {
    const XYZ c = linear_srgb_to_xyz(r, g, b);
    const XYZ white = srgb_white_xyz();
    // CIE 15:2004 Lab: f(t) = cbrt(t) above (6/29)^3, else the linear segment t/(3 (6/29)^2) +
    // 4/29.
    auto f = [](double t) {
        constexpr double d = 6.0 / 29.0;
        return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
    };
    const double fx = f(c.X / white.X), fy = f(c.Y / white.Y), fz = f(c.Z / white.Z);
    return Lab{116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Lab srgb8_to_lab(uint8_t r, uint8_t g, uint8_t b) {
    // 8-bit code -> linear, computed once (exact piecewise decoding, IEC 61966-2-1).
    static const std::array<double, 256> decode = [] {
        std::array<double, 256> t{};
        for (int i = 0; i < 256; ++i)
            t[i] = srgb_to_linear(i / 255.0);
        return t;
    }();
    return linear_srgb_to_lab(decode[r], decode[g], decode[b]);
}

double nearest_rank_percentile(std::span<double> values, unsigned percent) {
    if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
    // In integers, so that 0.99 * n cannot round up: rank = ceil(percent * n / 100).
    const std::size_t rank = (std::size_t{percent} * values.size() + 99) / 100;
    auto nth = values.begin() + static_cast<std::ptrdiff_t>(std::max<std::size_t>(rank, 1) - 1);
    std::nth_element(values.begin(), nth, values.end());
    return *nth;
}

std::vector<double> ciede2000_map(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                                  float exposure) {
    if (test.width != reference.width || test.height != reference.height || !test.well_formed() ||
        !reference.well_formed())
        return {};
    const std::vector<uint8_t> test8 = tone_map_to_srgb8(test, exposure);
    const std::vector<uint8_t> ref8 = tone_map_to_srgb8(reference, exposure);
    std::vector<double> map(test.pixel_count());
    for (std::size_t p = 0; p < map.size(); ++p) {
        const std::size_t i = p * 4;
        if (!finite_rgb(&test.rgba[i]) || !finite_rgb(&reference.rgba[i])) {
            map[p] = std::numeric_limits<double>::quiet_NaN();
            continue;
        }
        const uint8_t* t8 = &test8[i];
        const uint8_t* r8 = &ref8[i];
        const bool same = t8[0] == r8[0] && t8[1] == r8[1] && t8[2] == r8[2];
        map[p] =
            same ? 0.0
                 : ciede2000(srgb8_to_lab(t8[0], t8[1], t8[2]), srgb8_to_lab(r8[0], r8[1], r8[2]));
    }
    return map;
}

ImageErrorStats compare_images(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                               float exposure) {
    ImageErrorStats s;
    if (test.width != reference.width || test.height != reference.height) {
        s.error = fmt::format("image sizes differ: test is {}x{}, reference is {}x{}", test.width,
                              test.height, reference.width, reference.height);
        return s;
    }
    if (s.error = shape_error("test", test); !s.error.empty()) return s;
    if (s.error = shape_error("reference", reference); !s.error.empty()) return s;

    const std::vector<double> delta_e_map = ciede2000_map(test, reference, exposure);
    std::vector<double> delta_e;
    delta_e.reserve(test.pixel_count());

    s.pixel_count = test.pixel_count();
    double sum_sq = 0.0;
    for (uint32_t y = 0; y < test.height; ++y) {
        for (uint32_t x = 0; x < test.width; ++x) {
            const std::size_t p = std::size_t{y} * test.width + x, i = p * 4;
            const bool test_ok = finite_rgb(&test.rgba[i]);
            const bool ref_ok = finite_rgb(&reference.rgba[i]);
            s.nan_inf_pixels += test_ok ? 0 : 1;
            s.reference_nan_inf_pixels += ref_ok ? 0 : 1;
            s.nan_inf_where_reference_finite += (!test_ok && ref_ok) ? 1 : 0;
            if (!test_ok || !ref_ok) continue;
            ++s.compared_pixels;
            for (int c = 0; c < 3; ++c) {
                const double d = double(test.rgba[i + c]) - double(reference.rgba[i + c]);
                sum_sq += d * d;
                if (std::abs(d) > s.max_abs) {
                    s.max_abs = std::abs(d);
                    s.max_abs_location = {x, y};
                }
            }
            delta_e.push_back(delta_e_map[p]);
        }
    }

    if (s.compared_pixels == 0) {
        // Nothing comparable: make every "error below threshold" check fail.
        const double nan = std::numeric_limits<double>::quiet_NaN();
        s.max_abs = s.rmse = s.psnr_db = s.ciede2000_mean = s.ciede2000_p99 = nan;
        return s;
    }
    s.rmse = std::sqrt(sum_sq / (3.0 * double(s.compared_pixels)));
    s.psnr_db = s.rmse == 0.0 ? std::numeric_limits<double>::infinity()
                              : -20.0 * std::log10(s.rmse); // = 10 log10(1^2 / mse)

    double sum_e = 0.0;
    for (double e : delta_e)
        sum_e += e;
    s.ciede2000_mean = sum_e / double(delta_e.size());
    s.ciede2000_p99 = nearest_rank_percentile(delta_e, 99);
    return s;
}

bool is_degenerate(const ImageRGBA32F& image) {
    if (!image.well_formed() || image.pixel_count() == 0) return true;
    auto same = [](float u, float v) { return u == v || (std::isnan(u) && std::isnan(v)); };
    const float* first = image.rgba.data();
    for (std::size_t i = 4; i < image.rgba.size(); i += 4) {
        for (int c = 0; c < 3; ++c) {
            if (!same(image.rgba[i + c], first[c])) return false;
        }
    }
    return true;
}

} // namespace watergen
