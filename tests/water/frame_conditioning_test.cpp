// The conditioned wave formula (phases offset on the host, positions in the frame: frame.h)
// against the unconditioned one, f_i (d_i . x) + s_i t at the world point, in binary128: the
// CPU evaluator in double stays within 1e-9 m of it at a year and 1,000 km from the origin.
#include <catch2/catch.hpp>

#include <cmath>
#include <quadmath.h>

#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/water/mesh_shader.h"
#include "watergen/water/nodes/waves.h"
#include "waves_support.h"

using namespace watergen;

namespace {

// The sums over 004's four default waves at world (x, z) and time t, in binary128. f_i and a_i
// are the doubles the shader's loop makes (each the previous times the gain).
struct Exact {
    double height = 0, dx = 0, dy = 0, dz = 0;
};
Exact exact(const test::WaveModel& m, __float128 x, __float128 z, double t, bool gerstner) {
    Exact out;
    double f = m.frequency, a = m.amplitude;
    __float128 h = 0, px = 0, py = 0, pz = 0;
    for (int i = 0; i < m.count; ++i) {
        const __float128 th = __float128(f) * (__float128(m.dx(i)) * x + __float128(m.dz(i)) * z) +
                              __float128(t) * __float128(m.phase_speeds[size_t(i)]);
        h += __float128(a) * sinq(th);
        // GPU Gems' Q_i = Q / (w_i A_i n), as the shader computes it (in double here).
        const double qa = m.steepness / (m.count * std::max(f * a, 1e-6)) * a;
        px += __float128(qa) * m.dx(i) * cosq(th);
        py += __float128(a) * sinq(th);
        pz += __float128(qa) * m.dz(i) * cosq(th);
        f *= m.frequency_gain;
        a *= m.amplitude_gain;
    }
    out.height = double(h);
    if (gerstner) out = {double(h), double(px), double(py), double(pz)};
    return out;
}

} // namespace

TEST_CASE("conditioned waves match the unconditioned formula in binary128 to 1e-9 m",
          "[waves][frame]") {
    Graph g;
    Expr time = scene_time(g);
    scene_eye_position(g); // the frame follows the eye
    Expr xz = varying(g, "xz", Type::Vec2);
    g.set_output("h", sum_of_sines_height(g, xz, time).id());
    g.set_output("d", gerstner_displacement(g, xz, time).id());
    REQUIRE_FALSE(has_errors(g.diagnostics()));

    const double year = 365.25 * 86400, week = 604800;
    // Points of a view around the eye, in the frame: up to 700 m away.
    const std::vector<double> rel = {0.0,  0.0,   3.7,   -2.1,   -12.25,
                                     40.5, 250.0, -75.0, -700.0, 650.0};
    double worst = 0;
    for (double t : {0.0, week, year})
        for (const auto& eye : {std::array<double, 2>{0.0, -30.0},
                                {1e5 + 10.0, -1e5 - 20.0},
                                {1e6 + 3.0, 1e6 - 5.0},
                                {-1e6 - 31.0, 4e5 + 17.0}}) {
            EvalInputs in;
            in.uniforms["time"] = {t};
            in.uniforms["eye_position"] = {eye[0], 8.0, eye[1]};
            in.varyings["xz"] = rel;
            in.lanes = rel.size() / 2;
            const EvalResult h = evaluate(g, "h", in, EvalPrecision::Double);
            const EvalResult d = evaluate(g, "d", in, EvalPrecision::Double);
            REQUIRE(h.ok());
            REQUIRE(d.ok());
            const FrameCentre c = frame_centre_of(eye[0], eye[1]);
            for (size_t k = 0; k < in.lanes; ++k) {
                const __float128 x = __float128(c.x) + rel[2 * k],
                                 z = __float128(c.z) + rel[2 * k + 1];
                const Exact s = exact(test::sines_model(), x, z, t, false);
                const Exact q = exact(test::gerstner_model(), x, z, t, true);
                worst = std::max(
                    {worst, std::abs(h.values[k] - s.height), std::abs(d.values[3 * k] - q.dx),
                     std::abs(d.values[3 * k + 1] - q.dy), std::abs(d.values[3 * k + 2] - q.dz)});
            }
        }
    // What is left is double's own rounding of phases up to f_3 x 700 m + pi: ~1e-13 m.
    CHECK(worst < 1e-9);
}
