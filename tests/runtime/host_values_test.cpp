// The host values (runtime/host_values.h) against the same formulas in binary128: the phase and
// tile offsets keep about 1e-16 of their unreduced size at a year and 10,000 km, and the frame
// rules move positions and matrices so that the frame's point maps where the world's did.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <quadmath.h>
#include <string>
#include <vector>

#include "watergen/runtime/host_values.h"

using namespace watergen;

namespace {

// pi to 50 digits (M_PIq needs GNU literals, which -std=c++20 turns off).
const __float128 kPiQ =
    strtoflt128("3.14159265358979323846264338327950288419716939937510", nullptr);

// Reduced into [-pi, pi) in binary128 (113 bits: a phase of 1e10 keeps 1e-24 rad).
double reference_phase(double f, double dx, double dz, double s, double t, Frame fr) {
    const __float128 px = __float128(fr.origin.x) + fr.centre.x;
    const __float128 pz = __float128(fr.origin.z) + fr.centre.z;
    const __float128 phase =
        __float128(f) * (__float128(dx) * px + __float128(dz) * pz) + __float128(s) * __float128(t);
    __float128 r = fmodq(phase, 2 * kPiQ);
    if (r >= kPiQ) r -= 2 * kPiQ;
    if (r < -kPiQ) r += 2 * kPiQ;
    return double(r);
}

double reference_tile(double origin, double x, double scale, double rate, double t) {
    const __float128 u = (__float128(origin) + x) * __float128(scale) + __float128(rate) * t;
    __float128 r = u - floorq(u);
    return double(r);
}

// The distance between two angles, around the circle.
double angle_apart(double a, double b) {
    const double d = std::fmod(std::abs(a - b), 2 * M_PI);
    return std::min(d, 2 * M_PI - d);
}

} // namespace

TEST_CASE("wave phase offsets match binary128 to 1e-15 rad at a year and 10,000 km",
          "[host_values]") {
    // The sweep's extremes and the parameters' ranges: 004's eighth Gerstner wave
    // (0.7 x 1.18^7 rad/m, 4.68 rad/s), the fastest speed allowed (100 rad/s), a year.
    const double year = 365.25 * 86400;
    const double fs[] = {0.7, 0.7 * std::pow(1.18, 7), 100.0};
    const double speeds[] = {2.62, 4.68, -100.0};
    const double times[] = {0.0, 3600.0, 604800.0, year};
    const Frame frames[] = {{{0, 0}, {0, 0}},
                            {{1e5, -64}, {0, 0}},
                            {{-1e7, 1e7}, {0, 0}},
                            {{64, -128}, {123456.789, -98765.4321}}};
    double worst = 0;
    for (double f : fs)
        for (double s : speeds)
            for (double t : times)
                for (const Frame& fr : frames) {
                    const double got = wave_phase_offset(f, 0.6, -0.8, s, t, fr);
                    CHECK(got >= -M_PI);
                    CHECK(got < M_PI);
                    worst =
                        std::max(worst, angle_apart(got, reference_phase(f, 0.6, -0.8, s, t, fr)));
                }
    // The largest phase here is 100 x 1e7 + 100 x 3.2e7 = 4e9 rad; 1e-15 rad is 2.5e-25 of it:
    // what double-double (106 bits) and a 2 pi in three parts keep, with margin.
    CHECK(worst < 1e-15);
}

TEST_CASE("scroll offsets match binary128 and stay in [0, 1)", "[host_values]") {
    const double year = 365.25 * 86400;
    double worst = 0;
    for (double x : {0.0, 64.0, -1e5, 1e7})
        for (double origin : {0.0, 123456.789})
            for (double t : {0.0, 3600.0, year}) {
                const double got = scroll_offset(origin, x, 0.06, -0.02, t);
                CHECK(got >= 0.0);
                CHECK(got < 1.0);
                const double d = std::abs(got - reference_tile(origin, x, 0.06, -0.02, t));
                worst = std::max(worst, std::min(d, 1.0 - d));
            }
    CHECK(worst < 1e-15);
}

TEST_CASE("frame rules move points and matrices so the frame's point maps as the world's",
          "[host_values]") {
    const Frame frame{{1e5, -2e5}, {0, 0}};
    std::map<std::string, std::vector<double>> given = {
        {"c0", {0.9, 0.1, 0.0, 0.2}}, {"c2", {0.1, -0.3, 0.7, 0.5}}, {"flag", {0.0}}};
    const GivenValues read = [&](const std::string& n) -> const std::vector<double>* {
        auto it = given.find(n);
        return it == given.end() ? nullptr : &it->second;
    };
    std::string error;
    SECTION("a point loses the centre's x and z") {
        const auto v = host_value({HostRule::FramePoint, {}}, {100003.5, 8.0, -199990.25}, read,
                                  frame, &error);
        REQUIRE(v);
        CHECK(*v == std::vector<double>{3.5, 8.0, 9.75});
    }
    SECTION("world-to-clip: M (p + c) = M' p") {
        const std::vector<double> c3 = {1.0, 2.0, 3.0, 4.0};
        const auto v =
            host_value({HostRule::FrameWorldToClip, {"c0", "c2"}}, c3, read, frame, &error);
        REQUIRE(v);
        for (size_t k = 0; k < 4; ++k)
            CHECK((*v)[k] == Approx(c3[k] + given["c0"][k] * 1e5 + given["c2"][k] * -2e5));
    }
    SECTION("clip-to-world: a column loses the centre times its w, unless camera-relative") {
        const auto v = host_value({HostRule::FrameClipToWorld, {"flag"}}, {1e5, 2.0, -2e5, 1.0},
                                  read, frame, &error);
        REQUIRE(v);
        CHECK(*v == std::vector<double>{0.0, 2.0, 0.0, 1.0});
        given["flag"] = {1.0};
        const auto kept = host_value({HostRule::FrameClipToWorld, {"flag"}}, {1e5, 2.0, -2e5, 1.0},
                                     read, frame, &error);
        REQUIRE(kept);
        CHECK(*kept == std::vector<double>{1e5, 2.0, -2e5, 1.0});
    }
    SECTION("a tile offset is the centre modulo the tile") {
        given["size"] = {10.0};
        const auto v = host_value({HostRule::TileOffset, {"size"}}, {0, 0}, read,
                                  Frame{{1e5 + 3.0, -2e5 - 3.0}, {0, 0}}, &error);
        REQUIRE(v);
        CHECK((*v)[0] == Approx(0.3).margin(1e-12));
        CHECK((*v)[1] == Approx(0.7).margin(1e-12));
    }
    SECTION("a missing input names itself") {
        const auto v = host_value({HostRule::FrameWorldToClip, {"c0", "nope"}}, {0, 0, 0, 1}, read,
                                  frame, &error);
        CHECK_FALSE(v);
        CHECK(error == "host rule frame_world_to_clip reads 'nope', which has no value");
    }
}

TEST_CASE("the frame centre is the centre of the eye's whole-metre cell", "[host_values]") {
    CHECK(frame_centre_of(0.0, -0.3) == FrameCentre{0.5, -0.5});
    CHECK(frame_centre_of(0.99, 1.0) == FrameCentre{0.5, 1.5});
    CHECK(frame_centre_of(1e5 + 20.2, -1e6 - 40.7) == FrameCentre{100020.5, -1000040.5});
    // A step inside one cell keeps the centre (a vertex buffer stays: water_grid.h).
    CHECK(frame_centre_of(std::nextafter(4.0, 0.0), -5.99) == frame_centre_of(3.0, -5.01));
    const FrameCentre far = frame_centre_of(9.99e6 + 0.7, -9.99e6 - 0.7);
    CHECK(far == FrameCentre{9.99e6 + 0.5, -9.99e6 - 0.5});
}
