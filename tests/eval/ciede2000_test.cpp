// CIEDE2000 and sRGB -> Lab conversion.
#include <catch2/catch.hpp>

#include "watergen/eval/image/image_metrics.h"

using watergen::ciede2000;
using watergen::Lab;
using watergen::srgb8_to_lab;

namespace {

struct SharmaPair {
    int id;
    Lab first, second;
    double delta_e;
};

// All 34 pairs of Table 1 in Sharma, Wu, Dalal, "The CIEDE2000 color-difference formula:
// implementation notes, supplementary test data, and mathematical observations",
// Color Res. Appl. 30(1), 2005. The table gives dE00 to 4 decimals.
const SharmaPair kSharmaTable1[] = {
    {1, {50.0000, 2.6772, -79.7751}, {50.0000, 0.0000, -82.7485}, 2.0425},
    {2, {50.0000, 3.1571, -77.2803}, {50.0000, 0.0000, -82.7485}, 2.8615},
    {3, {50.0000, 2.8361, -74.0200}, {50.0000, 0.0000, -82.7485}, 3.4412},
    {4, {50.0000, -1.3802, -84.2814}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {5, {50.0000, -1.1848, -84.8006}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {6, {50.0000, -0.9009, -85.5211}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {7, {50.0000, 0.0000, 0.0000}, {50.0000, -1.0000, 2.0000}, 2.3669},
    {8, {50.0000, -1.0000, 2.0000}, {50.0000, 0.0000, 0.0000}, 2.3669},
    {9, {50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0009}, 7.1792},
    {10, {50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0010}, 7.1792},
    {11, {50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0011}, 7.2195},
    {12, {50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0012}, 7.2195},
    {13, {50.0000, -0.0010, 2.4900}, {50.0000, 0.0009, -2.4900}, 4.8045},
    {14, {50.0000, -0.0010, 2.4900}, {50.0000, 0.0010, -2.4900}, 4.8045},
    {15, {50.0000, -0.0010, 2.4900}, {50.0000, 0.0011, -2.4900}, 4.7461},
    {16, {50.0000, 2.5000, 0.0000}, {50.0000, 0.0000, -2.5000}, 4.3065},
    {17, {50.0000, 2.5000, 0.0000}, {73.0000, 25.0000, -18.0000}, 27.1492},
    {18, {50.0000, 2.5000, 0.0000}, {61.0000, -5.0000, 29.0000}, 22.8977},
    {19, {50.0000, 2.5000, 0.0000}, {56.0000, -27.0000, -3.0000}, 31.9030},
    {20, {50.0000, 2.5000, 0.0000}, {58.0000, 24.0000, 15.0000}, 19.4535},
    {21, {50.0000, 2.5000, 0.0000}, {50.0000, 3.1736, 0.5854}, 1.0000},
    {22, {50.0000, 2.5000, 0.0000}, {50.0000, 3.2972, 0.0000}, 1.0000},
    {23, {50.0000, 2.5000, 0.0000}, {50.0000, 1.8634, 0.5757}, 1.0000},
    {24, {50.0000, 2.5000, 0.0000}, {50.0000, 3.2592, 0.3350}, 1.0000},
    {25, {60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644},
    {26, {63.0109, -31.0961, -5.8663}, {62.8187, -29.7946, -4.0864}, 1.2630},
    {27, {61.2901, 3.7196, -5.3901}, {61.4292, 2.2480, -4.9620}, 1.8731},
    {28, {35.0831, -44.1164, 3.7933}, {35.0232, -40.0716, 1.5901}, 1.8645},
    {29, {22.7233, 20.0904, -46.6940}, {23.0331, 14.9730, -42.5619}, 2.0373},
    {30, {36.4612, 47.8580, 18.3852}, {36.2715, 50.5065, 21.2231}, 1.4146},
    {31, {90.8027, -2.0831, 1.4410}, {91.1528, -1.6435, 0.0447}, 1.4441},
    {32, {90.9257, -0.5406, -0.9208}, {88.6381, -0.8985, -0.7239}, 1.5381},
    {33, {6.7747, -0.2908, -2.4247}, {5.8714, -0.0985, -2.2286}, 0.6377},
    {34, {2.0776, 0.0795, -1.1350}, {0.9033, -0.0636, -0.5514}, 0.9082},
};

} // namespace

TEST_CASE("ciede2000 matches all 34 pairs of Sharma, Wu, Dalal (2005) Table 1 within 1e-4",
          "[unit][ciede2000]") {
    for (const SharmaPair& p : kSharmaTable1) {
        INFO("pair " << p.id);
        CHECK(ciede2000(p.first, p.second) == Approx(p.delta_e).margin(1e-4));
    }
}

TEST_CASE("ciede2000 is zero for identical colours, including achromatic ones",
          "[unit][ciede2000]") {
    CHECK(ciede2000({50, 0, 0}, {50, 0, 0}) == 0.0);
    CHECK(ciede2000({0, 0, 0}, {0, 0, 0}) == 0.0);
    CHECK(ciede2000({61.2901, 3.7196, -5.3901}, {61.2901, 3.7196, -5.3901}) == 0.0);
    // -0.0 components must not turn the hue of a grey into 180 degrees.
    CHECK(ciede2000({50, -0.0, -0.0}, {50, -1, 2}) == Approx(2.3669).margin(1e-4));
}

TEST_CASE("srgb8_to_lab maps white to L=100 and black to L=0 with a = b = 0", "[unit][ciede2000]") {
    const Lab white = srgb8_to_lab(255, 255, 255);
    CHECK(white.L == Approx(100.0).margin(1e-9));
    CHECK(white.a == Approx(0.0).margin(1e-9));
    CHECK(white.b == Approx(0.0).margin(1e-9));
    const Lab black = srgb8_to_lab(0, 0, 0);
    CHECK(black.L == Approx(0.0).margin(1e-12));
    CHECK(black.a == Approx(0.0).margin(1e-12));
    CHECK(black.b == Approx(0.0).margin(1e-12));
}

TEST_CASE("srgb8_to_lab keeps greys neutral and gives sRGB red its textbook Lab",
          "[unit][ciede2000]") {
    for (int v : {1, 10, 11, 50, 128, 200, 254}) {
        INFO("grey " << v);
        const auto g = static_cast<uint8_t>(v);
        const Lab lab = srgb8_to_lab(g, g, g);
        CHECK(lab.a == Approx(0.0).margin(1e-9));
        CHECK(lab.b == Approx(0.0).margin(1e-9));
    }
    // Grey 128 is 21.59% linear luminance -> L* = 53.59 (CIE 15 formula by hand).
    CHECK(srgb8_to_lab(128, 128, 128).L == Approx(53.585).margin(0.01));
    // Widely quoted value for sRGB red under D65: (53.24, 80.09, 67.20); the 4-decimal matrix
    // used here differs from other derivations in the second decimal.
    const Lab red = srgb8_to_lab(255, 0, 0);
    CHECK(red.L == Approx(53.24).margin(0.01));
    CHECK(red.a == Approx(80.09).margin(0.05));
    CHECK(red.b == Approx(67.20).margin(0.05));
}
