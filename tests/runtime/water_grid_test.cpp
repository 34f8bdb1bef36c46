// The clipmap grid of water_grid.h on the CPU: the levels tile the coarsest square once, the
// morph leaves no crack between levels for any eye of the snap, the counts, the winding, the
// errors, the draw order, and a grid that changes only with its snap.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <stdexcept>
#include <tuple>

#include "watergen/runtime/water_grid.h"

using namespace watergen;

namespace {

struct Vertex {
    double x, z, to_x, to_z, h;
};

// In world coordinates: the grid's floats are relative to its frame centre (exact in double).
Vertex vertex(const WaterGrid& g, uint32_t v) {
    const float* f = g.vertices.data() + size_t(v) * WaterGrid::kFloatsPerVertex;
    return {f[0] + g.origin.x, f[1] + g.origin.z, f[2], f[3], f[4]};
}

// A cell's corners a = (i, j), b = (i+1, j), c = (i, j+1), d = (i+1, j+1), in draw order.
struct Cell {
    uint32_t a, b, c, d;
};

std::vector<Cell> patches(const WaterGrid& g) {
    REQUIRE(g.topology == GridTopology::Patches);
    REQUIRE(g.indices.size() % 4 == 0);
    std::vector<Cell> out;
    for (size_t p = 0; p < g.indices.size(); p += 4)
        out.push_back({g.indices[p], g.indices[p + 1], g.indices[p + 2], g.indices[p + 3]});
    return out;
}

uint32_t level_of(const WaterGridDesc& d, double h) {
    const int k = int(std::lround(std::log2(h / d.spacing)));
    REQUIRE(std::ldexp(d.spacing, k) == Approx(h));
    return uint32_t(k);
}

double chebyshev(const Vertex& v, double cx, double cz) {
    return std::max(std::abs(v.x - cx), std::abs(v.z - cz));
}

// The shader's morph factor, from water_grid.h's formula.
double morph_t(const WaterGrid& g, const Vertex& v, double eye_x, double eye_z) {
    const double d = chebyshev(v, eye_x, eye_z) / v.h;
    return std::clamp((d - g.morph_start) / (g.morph_end - g.morph_start), 0.0, 1.0);
}

struct Centre {
    double x, z;
};

// c_k from the snap integers: floor(eye / (2 h_k)) 2 h_k.
Centre centre(const WaterGridDesc& d, const std::vector<std::array<int64_t, 2>>& snap, uint32_t k) {
    const double two_h = std::ldexp(d.spacing, int(k) + 1);
    return {double(snap[k][0]) * two_h, double(snap[k][1]) * two_h};
}

// Eyes: the origin, negative coordinates, exactly on snap boundaries of every level for
// spacing 0.5 (64 = 2 h_6, -16 = -2 h_4) and just below one, and far from the origin.
const std::vector<std::array<double, 2>> kEyes = {
    {0.0, 0.0},        {-0.3, -7.9}, {8.0, -16.0}, {-64.0, 64.0}, {std::nextafter(64.0, 0.0), -0.0},
    {12345.6, -9876.5}};

bool same_bytes(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

} // namespace

TEST_CASE("water grid levels tile the coarsest square exactly once", "[water_grid]") {
    // Spacing 0.3 is not dyadic: its floats are rounded, but each cell still lands on its
    // finest-grid cells.
    const std::vector<WaterGridDesc> descs = {
        {0.5, 16, 6}, {0.5, 32, 4}, {0.25, 18, 5}, {0.3, 16, 4}};
    // A subnormal eye too (-denorm_min / 2 rounds to -0: see the snap test).
    auto eyes = kEyes;
    const double tiny = std::numeric_limits<double>::denorm_min();
    eyes.push_back({-tiny, -tiny});
    for (const WaterGridDesc& d : descs)
        for (const auto& [ex, ez] : eyes) {
            if (d.spacing == 0.3 && std::abs(ex) > 1000) continue; // float rounding > 1e-3 m
            INFO("spacing " << d.spacing << " n " << d.ring_cells << " L " << d.levels << " eye "
                            << ex << ", " << ez);
            const WaterGrid g = water_grid(d, ex, ez, GridTopology::Patches);
            const auto snap = water_grid_snap(d, ex, ez);
            const uint32_t top = d.levels - 1;
            const double coarse_h = std::ldexp(d.spacing, int(top));
            const Centre c = centre(d, snap, top);
            const double x0 = c.x - d.ring_cells * coarse_h, z0 = c.z - d.ring_cells * coarse_h;
            // The coarsest square in finest cells, rasterised with integers.
            const int64_t side = int64_t(2 * d.ring_cells) << top;
            std::vector<uint8_t> covered(size_t(side * side), 0);
            uint64_t overlaps = 0, outside = 0;
            double area = 0;
            for (const Cell& cell : patches(g)) {
                const Vertex a = vertex(g, cell.a), b = vertex(g, cell.b), cc = vertex(g, cell.c),
                             dd = vertex(g, cell.d);
                const double h = a.h, tol = 1e-3 * d.spacing;
                REQUIRE(b.x - a.x == Approx(h).margin(tol));
                REQUIRE(b.z - a.z == Approx(0).margin(tol));
                REQUIRE(cc.x - a.x == Approx(0).margin(tol));
                REQUIRE(cc.z - a.z == Approx(h).margin(tol));
                REQUIRE(dd.x - a.x == Approx(h).margin(tol));
                REQUIRE(dd.z - a.z == Approx(h).margin(tol));
                const uint32_t k = level_of(d, h);
                area += std::ldexp(d.spacing, int(k)) * std::ldexp(d.spacing, int(k));
                const int64_t gx = std::llround((a.x - x0) / d.spacing);
                const int64_t gz = std::llround((a.z - z0) / d.spacing);
                const int64_t size = int64_t(1) << k;
                if (gx < 0 || gz < 0 || gx + size > side || gz + size > side) {
                    ++outside;
                    continue;
                }
                for (int64_t z = gz; z < gz + size; ++z)
                    for (int64_t x = gx; x < gx + size; ++x)
                        if (covered[size_t(z * side + x)]++) ++overlaps;
            }
            CHECK(outside == 0);
            CHECK(overlaps == 0);
            CHECK(std::count(covered.begin(), covered.end(), 0) == 0);
            const double square = 2.0 * d.ring_cells * coarse_h;
            CHECK(area == Approx(square * square).epsilon(1e-12));
        }
}

TEST_CASE("water grid snaps are floor(eye / (2 h_k)), on boundaries too", "[water_grid]") {
    const WaterGridDesc d{0.5, 16, 8};
    for (const auto& [ex, ez] : kEyes) {
        const auto snap = water_grid_snap(d, ex, ez);
        REQUIRE(snap.size() == 8);
        for (uint32_t k = 0; k < 8; ++k) {
            const double two_h = std::ldexp(d.spacing, int(k) + 1);
            CHECK(snap[k][0] == int64_t(std::floor(ex / two_h)));
            CHECK(snap[k][1] == int64_t(std::floor(ez / two_h)));
        }
    }
    // 64 m is 2 h_k times an integer for k <= 6: on the boundary the eye's snap cell is the
    // one that starts there, just below it the one before.
    CHECK(water_grid_snap(d, 64.0, -16.0)[6] == std::array<int64_t, 2>{1, -1});
    CHECK(water_grid_snap(d, 64.0, -16.0)[4] == std::array<int64_t, 2>{4, -1});
    CHECK(water_grid_snap(d, std::nextafter(64.0, 0.0), 0.0)[6] == std::array<int64_t, 2>{0, 0});
    CHECK(water_grid_snap(d, -0.3, -7.9)[0] == std::array<int64_t, 2>{-1, -8});
    CHECK(water_grid_snap(d, 12345.6, -9876.5)[0] == std::array<int64_t, 2>{12345, -9877});
    // floor(-denorm_min / (2 h_k)) is -1 at every level, though the division by 2 h_1 rounds
    // to -0 in floating point (a snap of 0 there would make o = -1).
    const double tiny = std::numeric_limits<double>::denorm_min();
    for (const auto& s : water_grid_snap(d, -tiny, tiny))
        CHECK(s == std::array<int64_t, 2>{-1, 0});
}

TEST_CASE("water grid morphing leaves no crack between levels", "[water_grid]") {
    // Dyadic spacings: every grid point and morphed point is exact in float, so the levels
    // must meet to within 1e-9 m even at (12345.6, -9876.5).
    const std::vector<WaterGridDesc> descs = {{0.5, 16, 5}, {0.25, 32, 4}, {0.5, 20, 3}};
    for (const WaterGridDesc& d : descs)
        for (const auto& [ex, ez] : kEyes) {
            const WaterGrid g = water_grid(d, ex, ez, GridTopology::Triangles);
            const auto snap = water_grid_snap(d, ex, ez);
            const uint32_t n = d.ring_cells;
            std::vector<std::vector<uint32_t>> by_level(d.levels);
            for (uint32_t v = 0; v < g.vertex_count(); ++v)
                by_level[level_of(d, vertex(g, v).h)].push_back(v);

            // to_coarse: -h on each axis where the vertex is odd relative to c_k.
            for (uint32_t k = 0; k < d.levels; ++k) {
                const Centre c = centre(d, snap, k);
                for (uint32_t v : by_level[k]) {
                    const Vertex p = vertex(g, v);
                    const int64_t i = std::llround((p.x - c.x) / p.h);
                    const int64_t j = std::llround((p.z - c.z) / p.h);
                    REQUIRE(p.to_x == ((i & 1) ? -p.h : 0.0));
                    REQUIRE(p.to_z == ((j & 1) ? -p.h : 0.0));
                }
            }

            // The shader morphs with the eye of each frame: every eye of the finest snap cell
            // (its corners included) must leave no crack in the grid built for it.
            const Centre c0 = centre(d, snap, 0);
            const double top = std::nextafter(c0.x + 2 * d.spacing, c0.x);
            const double right = std::nextafter(c0.z + 2 * d.spacing, c0.z);
            const std::vector<std::array<double, 2>> frame_eyes = {
                {ex, ez}, {c0.x, c0.z}, {top, right}, {top, c0.z}, {c0.x, right}};
            for (const auto& [fx, fz] : frame_eyes) {
                INFO("spacing " << d.spacing << " n " << n << " L " << d.levels << " eye " << ex
                                << ", " << ez << " frame eye " << fx << ", " << fz);
                for (uint32_t k = 1; k < d.levels; ++k) {
                    // Level k - 1's outer edge and level k's inner (hole) edge: the same square.
                    const Centre inner_c = centre(d, snap, k - 1);
                    const double half = n * std::ldexp(d.spacing, int(k) - 1);
                    std::vector<uint32_t> outer, inner;
                    for (uint32_t v : by_level[k - 1])
                        if (std::abs(chebyshev(vertex(g, v), inner_c.x, inner_c.z) - half) < 1e-9)
                            outer.push_back(v);
                    for (uint32_t v : by_level[k])
                        if (std::abs(chebyshev(vertex(g, v), inner_c.x, inner_c.z) - half) < 1e-9)
                            inner.push_back(v);
                    REQUIRE(outer.size() == 8 * n); // 2n cells a side
                    REQUIRE(inner.size() == 4 * n); // n cells a side
                    for (uint32_t v : inner) {
                        const Vertex p = vertex(g, v);
                        CHECK(morph_t(g, p, fx, fz) == 0.0);
                        CHECK(water_grid_morphed(g, v, fx, fz) == std::array<double, 2>{p.x, p.z});
                    }
                    std::set<uint32_t> met;
                    for (uint32_t v : outer) {
                        CHECK(morph_t(g, vertex(g, v), fx, fz) == 1.0);
                        const auto m = water_grid_morphed(g, v, fx, fz);
                        const auto hit = std::find_if(inner.begin(), inner.end(), [&](uint32_t w) {
                            const Vertex q = vertex(g, w);
                            return std::abs(m[0] - q.x) <= 1e-9 && std::abs(m[1] - q.z) <= 1e-9;
                        });
                        CHECK(hit != inner.end());
                        if (hit != inner.end()) met.insert(*hit);
                    }
                    // Both sides of the seam have exactly the same vertices (no T-junction).
                    CHECK(met.size() == inner.size());
                }
                // A vertex mid-morph is strictly inside its ring: never on an edge.
                for (uint32_t k = 0; k < d.levels; ++k) {
                    const Centre c = centre(d, snap, k);
                    const double h = std::ldexp(d.spacing, int(k));
                    for (uint32_t v : by_level[k]) {
                        const Vertex p = vertex(g, v);
                        const double t = morph_t(g, p, fx, fz);
                        if (t <= 0.0 || t >= 1.0) continue;
                        CHECK(chebyshev(p, c.x, c.z) < n * h - 1e-9);
                        if (k > 0) {
                            const Centre ci = centre(d, snap, k - 1);
                            CHECK(chebyshev(p, ci.x, ci.z) > n * h / 2 + 1e-9);
                        }
                    }
                }
            }
        }
}

TEST_CASE("water grid counts", "[water_grid]") {
    // n = 16, L = 3 by hand. Level 0: vertices (2n + 1)^2 = 33^2 = 1089, cells (2n)^2 = 1024.
    // Levels 1 and 2: the square's 1089 vertices less the hole's (n - 1)^2 = 15^2 = 225
    // interior ones = 864; cells 1024 - (n)^2 = 1024 - 256 = 768. Total: 1089 + 2 * 864 = 2817
    // vertices, 1024 + 2 * 768 = 2560 cells: 15360 triangle indices, 10240 patch indices.
    const WaterGridDesc d{0.5, 16, 3};
    CHECK(water_grid_vertex_count(d) == 2817);
    const WaterGrid tri = water_grid(d, 1.7, -2.2, GridTopology::Triangles);
    const WaterGrid quad = water_grid(d, 1.7, -2.2, GridTopology::Patches);
    CHECK(tri.vertex_count() == 2817);
    CHECK(tri.vertices.size() == 2817 * 5);
    CHECK(tri.indices.size() == 15360);
    CHECK(quad.indices.size() == 10240);
    CHECK(tri.patch_control_points == 0);
    CHECK(quad.patch_control_points == 4);
    CHECK(tri.morph_start == 12.0); // n/2 + 4
    CHECK(tri.morph_end == 13.0);   // n - 3
    std::array<uint32_t, 3> vertices_per_level{}, cells_per_level{};
    for (uint32_t v = 0; v < quad.vertex_count(); ++v)
        ++vertices_per_level[level_of(d, vertex(quad, v).h)];
    for (const Cell& c : patches(quad))
        ++cells_per_level[level_of(d, vertex(quad, c.a).h)];
    CHECK(vertices_per_level == std::array<uint32_t, 3>{1089, 864, 864});
    CHECK(cells_per_level == std::array<uint32_t, 3>{1024, 768, 768});

    // The same vertices either way; each patch a, b, c, d is the triangles (a, b, c), (b, d, c).
    CHECK(same_bytes(tri.vertices, quad.vertices));
    std::vector<uint32_t> expanded;
    for (const Cell& c : patches(quad))
        expanded.insert(expanded.end(), {c.a, c.b, c.c, c.b, c.d, c.c});
    CHECK(expanded == tri.indices);

    // The count does not depend on where the holes sit (o = 0 or 1 per axis, per level).
    const std::vector<WaterGridDesc> descs = {
        {0.5, 16, 3}, {0.25, 18, 5}, {1.0, 64, 1}, {0.5, 32, 8}};
    for (const WaterGridDesc& e : descs)
        for (const auto& [ex, ez] : kEyes) {
            INFO("n " << e.ring_cells << " L " << e.levels << " eye " << ex << ", " << ez);
            const WaterGrid g = water_grid(e, ex, ez, GridTopology::Patches);
            CHECK(g.vertex_count() == water_grid_vertex_count(e));
            const uint64_t n = e.ring_cells;
            CHECK(g.indices.size() == 4 * (4 * n * n + (e.levels - 1) * 3 * n * n));
            CHECK(std::all_of(g.indices.begin(), g.indices.end(),
                              [&](uint32_t i) { return i < g.vertex_count(); }));
        }
}

TEST_CASE("water grid triangles are counter-clockwise in (x, z)", "[water_grid]") {
    const WaterGridDesc d{0.5, 16, 4};
    for (const auto& [ex, ez] : kEyes) {
        const WaterGrid g = water_grid(d, ex, ez, GridTopology::Triangles);
        REQUIRE(g.indices.size() % 3 == 0);
        uint64_t level0 = 0, positive = 0, all_positive = 0;
        for (size_t t = 0; t < g.indices.size(); t += 3) {
            const Vertex a = vertex(g, g.indices[t]), b = vertex(g, g.indices[t + 1]),
                         c = vertex(g, g.indices[t + 2]);
            const double cross = (b.x - a.x) * (c.z - a.z) - (b.z - a.z) * (c.x - a.x);
            all_positive += cross > 0;
            if (a.h != d.spacing) continue;
            ++level0;
            positive += cross > 0;
        }
        CHECK(level0 == 2 * 32 * 32);
        CHECK(positive == level0);
        CHECK(all_positive == g.indices.size() / 3); // the rings too
    }
}

TEST_CASE("water grid errors name the field", "[water_grid]") {
    const auto error_of = [](WaterGridDesc d) {
        const auto e = water_grid_error(d);
        return e ? *e : std::string();
    };
    const auto has = [](const std::string& text, const std::string& part) {
        INFO(text);
        return text.find(part) != std::string::npos;
    };
    CHECK(!water_grid_error(WaterGridDesc{}));
    CHECK(has(error_of({0.0, 32, 8}), "spacing 0 m"));
    CHECK(has(error_of({2e3, 32, 8}), "spacing 2000 m"));
    CHECK(has(error_of({2e3, 32, 8}), "[0.001, 1000]"));
    CHECK(has(error_of({std::nan(""), 32, 8}), "spacing"));
    CHECK(has(error_of({0.5, 15, 8}), "ring_cells 15"));
    CHECK(has(error_of({0.5, 15, 8}), "even"));
    CHECK(has(error_of({0.5, 14, 8}), "ring_cells 14"));
    CHECK(has(error_of({0.5, 1024, 8}), "ring_cells 1024"));
    CHECK(has(error_of({0.5, 14, 8}), "[16, 512]"));
    CHECK(has(error_of({0.5, 32, 0}), "levels 0"));
    CHECK(has(error_of({0.5, 32, 17}), "levels 17"));
    CHECK(has(error_of({0.5, 32, 17}), "[1, 16]"));
    // Over the cap: 1025^2 + 15 (1025^2 - 511^2) = 1050625 + 15 * 789504 = 12893185 vertices.
    CHECK(water_grid_vertex_count({0.5, 512, 16}) == 12893185);
    const std::string cap = error_of({0.5, 512, 16});
    CHECK(has(cap, "ring_cells 512"));
    CHECK(has(cap, "levels 16"));
    CHECK(has(cap, "12893185"));
    CHECK(has(cap, "4194304"));
    // The cap's edge: 1050625 + 3 * 789504 = 3419137 fits, one more level (4208641) does not.
    CHECK(!water_grid_error({0.5, 512, 4}));
    CHECK(has(error_of({0.5, 512, 5}), "4208641"));

    CHECK_THROWS_AS(water_grid({0.0, 32, 8}, 0, 0, GridTopology::Triangles), std::invalid_argument);
    CHECK_THROWS_WITH(water_grid({0.5, 15, 8}, 0, 0, GridTopology::Patches),
                      error_of({0.5, 15, 8}));
    CHECK_THROWS_AS(water_grid({0.5, 512, 16}, 0, 0, GridTopology::Patches), std::invalid_argument);
    CHECK_THROWS_AS(water_grid_snap({0.5, 32, 0}, 0, 0), std::invalid_argument);
    CHECK_THROWS_AS(water_grid_vertex_count({0.5, 0, 8}), std::invalid_argument);
    // An eye the snap integers cannot hold.
    CHECK_THROWS_AS(water_grid(WaterGridDesc{}, std::nan(""), 0, GridTopology::Triangles),
                    std::invalid_argument);
    CHECK_THROWS_AS(water_grid_snap(WaterGridDesc{}, 0, std::numeric_limits<double>::infinity()),
                    std::invalid_argument);
    CHECK_THROWS_AS(water_grid_snap(WaterGridDesc{}, 1e300, 0), std::invalid_argument);
    const WaterGrid g = water_grid({0.5, 16, 1}, 0, 0, GridTopology::Triangles);
    CHECK_THROWS_AS(water_grid_morphed(g, g.vertex_count(), 0, 0), std::out_of_range);
}

TEST_CASE("water grid draws coarsest level first, far cells before near", "[water_grid]") {
    // Dyadic eye and spacing: the test's distances are exact, so ties are ties.
    const WaterGridDesc d{0.5, 16, 4};
    for (const auto& [ex, ez] : std::vector<std::array<double, 2>>{{3.25, -5.75}, {0, 0}}) {
        const WaterGrid g = water_grid(d, ex, ez, GridTopology::Patches);
        double last_h = std::numeric_limits<double>::infinity();
        std::tuple<double, double, double> last{}; // (-distance, z, x) of the previous cell
        for (const Cell& c : patches(g)) {
            const Vertex a = vertex(g, c.a);
            const double distance =
                std::max(std::abs(a.x + a.h / 2 - ex), std::abs(a.z + a.h / 2 - ez)) / a.h;
            const std::tuple<double, double, double> key{-distance, a.z, a.x};
            REQUIRE(a.h <= last_h);
            if (a.h == last_h) REQUIRE(last < key);
            last_h = a.h;
            last = key;
        }
        CHECK(last_h == d.spacing);       // the finest level last, its nearest cell at the very end
        CHECK(-std::get<0>(last) <= 0.5); // the eye's own cell, or one beside the eye
    }
}

TEST_CASE("water grid is deterministic and changes only with its snap", "[water_grid]") {
    const WaterGridDesc d{0.5, 16, 5};
    const WaterGrid a = water_grid(d, 3.2, -5.7, GridTopology::Triangles);
    const WaterGrid b = water_grid(d, 3.2, -5.7, GridTopology::Triangles);
    CHECK(same_bytes(a.vertices, b.vertices));
    CHECK(a.indices == b.indices);

    // The finest snap cell of (3.2, -5.7) is [3, 4) x [-6, -5) (2 h_0 = 1 m): anywhere in it
    // the snap and the vertices stay; the cells are the same, only their order may follow the
    // eye.
    const auto snap = water_grid_snap(d, 3.2, -5.7);
    const auto cells = [](const WaterGrid& g) {
        std::multiset<std::array<uint32_t, 6>> out;
        for (size_t t = 0; t < g.indices.size(); t += 6)
            out.insert(std::array<uint32_t, 6>{g.indices[t], g.indices[t + 1], g.indices[t + 2],
                                               g.indices[t + 3], g.indices[t + 4],
                                               g.indices[t + 5]});
        return out;
    };
    for (const auto& [ex, ez] : std::vector<std::array<double, 2>>{
             {3.0, -6.0}, {3.99, -5.01}, {std::nextafter(4.0, 0.0), -5.5}, {3.5, -5.99}}) {
        INFO("eye " << ex << ", " << ez);
        CHECK(water_grid_snap(d, ex, ez) == snap);
        const WaterGrid moved = water_grid(d, ex, ez, GridTopology::Triangles);
        CHECK(same_bytes(moved.vertices, a.vertices));
        CHECK(cells(moved) == cells(a));
    }
    // Across a boundary of the finest level the snap and the vertices change.
    for (const auto& [ex, ez] : std::vector<std::array<double, 2>>{{4.0, -5.7}, {3.2, -6.01}}) {
        CHECK(water_grid_snap(d, ex, ez) != snap);
        CHECK(!same_bytes(water_grid(d, ex, ez, GridTopology::Triangles).vertices, a.vertices));
    }
}
