// sin and cos together, for float storage: the evaluator's float(std::sin(double(x))) and
// float(std::cos(double(x))) of a binary32 x, computed for a row of lanes at once.
//
// Both are computed in double, without branches so that they vectorise: x reduced by multiples
// of pi/2 (Cody-Waite, pi/2 in four parts) and fdlibm's kernels (k_sin.c, k_cos.c: within
// 2^-58 on [-pi/4, pi/4]), to within about 2^-52. Where a result lies within 2^-40 (relative)
// of a binary32 rounding boundary, or |x| > 2^24 (the phases of the gold variant reach 2^21), or x
// is not finite, std::sin and std::cos decide, so a lane gets what they would give. Checked against
// them for every binary32 input (the SSE2 and the AVX2 build), and in tests/ir on a sample.
#include "block_kernels.h"

#include <cmath>

namespace watergen {

namespace {

constexpr double kMagic = 0x1.8p52; // (v + kMagic) - kMagic rounds v to an integer, |v| < 2^51
constexpr double kInvPio2 = 6.36619772367581382433e-01;
// pi/2 in four parts, the first three of 29 bits: k * part is exact for |k| < 2^24.
constexpr double kPio2[4] = {0x1.921fb54p+0, 0x1.10b4612p-30, -0x1.676733bp-60,
                             0x1.701b839a25205p-92};
constexpr double kLimit = 0x1p24;
constexpr double kMargin = 0x1p-40;

[[gnu::always_inline]] inline bool near_boundary(double y) {
    const double e = std::fabs(y) * kMargin;
    return static_cast<float>(y - e) != static_cast<float>(y + e);
}

template <unsigned LA>
[[gnu::always_inline]] inline void sincos_rows(const float* __restrict a, float* __restrict s,
                                               float* __restrict c, size_t n) {
    double ys[kBlock], yc[kBlock];
    unsigned char fallback[kBlock];
    for (size_t l = 0; l < n; ++l) {
        const double x = a[l * LA];
        const double k = (x * kInvPio2 + kMagic) - kMagic;
        const double r = (((x - k * kPio2[0]) - k * kPio2[1]) - k * kPio2[2]) - k * kPio2[3];
        const double z = r * r, w = z * z;
        const double rs = 8.33333333332248946124e-03 +
                          z * (-1.98412698298579493134e-04 + z * 2.75573137070700676789e-06) +
                          z * w * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10);
        // sin(+-0) is x itself (r may be +0 for x = -0, and r + z r (...) is +0 for r = -0).
        const double sin_r = x == 0.0 ? x : r + z * r * (-1.66666666666666324348e-01 + z * rs);
        const double rc = z * (4.16666666666666019037e-02 +
                               z * (-1.38888888888741095749e-03 + z * 2.48015872894767294178e-05)) +
                          w * w *
                              (-2.75573143513906633035e-07 +
                               z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11));
        const double hz = 0.5 * z, v = 1.0 - hz;
        const double cos_r = v + (((1.0 - v) - hz) + z * rc);
        // Quadrant k mod 4: x = r + k pi/2. Bitwise logic, no branches.
        const double h = k * 0.25;
        double fh = (h + kMagic) - kMagic;
        fh = fh > h ? fh - 1.0 : fh;
        const double q = k - 4.0 * fh;
        const bool odd = int(q == 1.0) | int(q == 3.0);
        const double sv = odd ? cos_r : sin_r, cv = odd ? sin_r : cos_r;
        ys[l] = q >= 2.0 ? -sv : sv;
        yc[l] = (int(q == 1.0) | int(q == 2.0)) ? -cv : cv;
        fallback[l] = static_cast<unsigned char>(
            int(!(std::fabs(x) <= kLimit)) | int(near_boundary(ys[l])) | int(near_boundary(yc[l])));
    }
    for (size_t l = 0; l < n; ++l)
        if (fallback[l]) {
            const double x = a[l * LA];
            ys[l] = std::sin(x);
            yc[l] = std::cos(x);
        }
    for (size_t l = 0; l < n; ++l) {
        s[l] = static_cast<float>(ys[l]);
        c[l] = static_cast<float>(yc[l]);
    }
}

template <unsigned LA> void sincos_sse2(const float* a, float* s, float* c, size_t n) {
    sincos_rows<LA>(a, s, c, n);
}
// The same code four lanes to a register; AVX2 without FMA computes exactly what SSE2 does.
template <unsigned LA>
[[gnu::target("avx2")]] void sincos_avx2(const float* a, float* s, float* c, size_t n) {
    sincos_rows<LA>(a, s, c, n);
}

// Instr::out: row 0 the sines, row 1 the cosines.
template <unsigned LA, bool Avx2> void sincos(const Instr& ins, Exec& ex, size_t n) {
    float* m = static_cast<float*>(ex.arena);
    float* s = m + ins.out.offset;
    if constexpr (Avx2)
        sincos_avx2<LA>(m + ins.args[0].offset, s, s + ins.out.comp_step, n);
    else
        sincos_sse2<LA>(m + ins.args[0].offset, s, s + ins.out.comp_step, n);
}

} // namespace

Kernel sincos_kernel(uint32_t lane_step) {
    static const bool avx2 = __builtin_cpu_supports("avx2");
    if (avx2) return lane_step ? sincos<1, true> : sincos<0, true>;
    return lane_step ? sincos<1, false> : sincos<0, false>;
}

} // namespace watergen
