// The clipmap rings of water_grid.h: the snapped centres, each level's kept cells and
// vertices, and the draw order.
#include "watergen/runtime/water_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <tuple>

namespace watergen {

namespace {

// Past 2^50 spacings from the origin the finest-grid integers below (eye / h_0 plus a ring)
// would no longer be exact in a double.
constexpr double kMaxEyeSpacings = 0x1p50;

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%g", v);
    return buf;
}

std::optional<std::string> field_error(const WaterGridDesc& d) {
    if (!(d.spacing >= 1e-3 && d.spacing <= 1e3))
        return "water grid spacing " + number(d.spacing) +
               " m is out of range: expected [0.001, 1000] m";
    if (d.ring_cells < 16 || d.ring_cells > 512 || d.ring_cells % 2 != 0)
        return "water grid ring_cells " + std::to_string(d.ring_cells) +
               " is out of range: expected an even number in [16, 512]";
    if (d.levels < 1 || d.levels > 16)
        return "water grid levels " + std::to_string(d.levels) +
               " is out of range: expected [1, 16]";
    return std::nullopt;
}

void require_valid(const WaterGridDesc& d) {
    if (const auto e = water_grid_error(d)) throw std::invalid_argument(*e);
}

int64_t finest_snap(double eye, double spacing, const char* axis) {
    if (!std::isfinite(eye) || std::abs(eye) / spacing > kMaxEyeSpacings)
        throw std::invalid_argument(std::string("water grid eye ") + axis + " " + number(eye) +
                                    " m: expected a finite value within 2^50 spacings (" +
                                    number(spacing) + " m) of the origin");
    return static_cast<int64_t>(std::floor(eye / (2 * spacing)));
}

// Every level's snap is the finest one floor-divided by 2^k (an arithmetic shift): the same
// integers as floor(eye / (2 h_k)), but from one rounding, so that o = s_{k-1} - 2 s_k is 0 or 1
// even where separate divisions disagree (-denorm_min / 2 rounds to -0, a snap of 0, not -1).
std::vector<std::array<int64_t, 2>> snaps(const WaterGridDesc& d, double eye_x, double eye_z) {
    const int64_t sx = finest_snap(eye_x, d.spacing, "x");
    const int64_t sz = finest_snap(eye_z, d.spacing, "z");
    std::vector<std::array<int64_t, 2>> out(d.levels);
    for (uint32_t k = 0; k < d.levels; ++k)
        out[k] = {sx >> k, sz >> k};
    return out;
}

// The finest-grid coordinate (units of h_0) of vertex i of level k around `snap`. Positions
// come from this one integer so that a point two levels share is the same float on both.
int64_t fine(int64_t snap, int64_t i, uint32_t k) {
    return (2 * snap + i) * (int64_t(1) << k);
}

struct Level {
    uint32_t k = 0;
    std::array<int64_t, 2> snap{};
    bool has_hole = false;
    std::array<int64_t, 2> hole{}; // o per axis: the hole is cells [o - n/2, o + n/2)
};

struct Cell {
    double distance; // Chebyshev, of the cell's centre from the eye, in cells
    int32_t i, j;
};

void add_level(const WaterGridDesc& d, const Level& level, double eye_x, double eye_z,
               WaterGrid& out) {
    const int32_t n = int32_t(d.ring_cells), side = 2 * n + 1;
    const double h = std::ldexp(d.spacing, int(level.k));
    const float to_coarse = -float(h);
    const auto kept = [&](int32_t i, int32_t j) {
        const auto in_hole = [&](int32_t c, int64_t o) { return c >= o - n / 2 && c < o + n / 2; };
        return !(level.has_hole && in_hole(i, level.hole[0]) && in_hole(j, level.hole[1]));
    };
    // The eye relative to c_k, in cells: [0, 2) per axis.
    const double ex = (eye_x - double(fine(level.snap[0], 0, level.k)) * d.spacing) / h;
    const double ez = (eye_z - double(fine(level.snap[1], 0, level.k)) * d.spacing) / h;

    std::vector<Cell> cells;
    std::vector<uint32_t> index(size_t(side) * side, UINT32_MAX);
    const auto at = [&](int32_t i, int32_t j) -> uint32_t& {
        return index[size_t(j + n) * side + size_t(i + n)];
    };
    for (int32_t j = -n; j < n; ++j)
        for (int32_t i = -n; i < n; ++i) {
            if (!kept(i, j)) continue;
            cells.push_back({std::max(std::abs(i + 0.5 - ex), std::abs(j + 0.5 - ez)), i, j});
            at(i, j) = at(i + 1, j) = at(i, j + 1) = at(i + 1, j + 1) = 0; // used
        }
    for (int32_t j = -n; j <= n; ++j)
        for (int32_t i = -n; i <= n; ++i) {
            if (at(i, j) == UINT32_MAX) continue;
            at(i, j) = out.vertex_count();
            // Exact in double (integers times a spacing, less a whole number of metres), then
            // rounded once.
            out.vertices.insert(
                out.vertices.end(),
                {float(double(fine(level.snap[0], i, level.k)) * d.spacing - out.origin.x),
                 float(double(fine(level.snap[1], j, level.k)) * d.spacing - out.origin.z),
                 (i & 1) ? to_coarse : 0.0f, (j & 1) ? to_coarse : 0.0f, float(h)});
        }

    // Farthest first, so that nearer cells overwrite them without a depth buffer; (j, i) makes
    // the order total, hence deterministic.
    std::sort(cells.begin(), cells.end(), [](const Cell& a, const Cell& b) {
        if (a.distance != b.distance) return a.distance > b.distance;
        return std::tie(a.j, a.i) < std::tie(b.j, b.i);
    });
    for (const Cell& c : cells) {
        const uint32_t a = at(c.i, c.j), b = at(c.i + 1, c.j), cc = at(c.i, c.j + 1),
                       dd = at(c.i + 1, c.j + 1);
        if (out.topology == GridTopology::Patches)
            out.indices.insert(out.indices.end(), {a, b, cc, dd});
        else
            out.indices.insert(out.indices.end(), {a, b, cc, b, dd, cc});
    }
}

} // namespace

uint64_t water_grid_vertex_count(const WaterGridDesc& desc) {
    if (const auto e = field_error(desc)) throw std::invalid_argument(*e);
    const uint64_t n = desc.ring_cells;
    const uint64_t square = (2 * n + 1) * (2 * n + 1);
    // The hole's boundary vertices belong to the ring's cells too (the hole lies strictly
    // inside the square for n >= 16), only its (n - 1)^2 interior ones are unused.
    const uint64_t ring = square - (n - 1) * (n - 1);
    return square + uint64_t(desc.levels - 1) * ring;
}

std::optional<std::string> water_grid_error(const WaterGridDesc& desc) {
    if (auto e = field_error(desc)) return e;
    if (const uint64_t count = water_grid_vertex_count(desc); count > kMaxWaterGridVertices)
        return "water grid ring_cells " + std::to_string(desc.ring_cells) + " and levels " +
               std::to_string(desc.levels) + " make " + std::to_string(count) +
               " vertices, over the cap of " + std::to_string(kMaxWaterGridVertices) +
               ": fewer ring_cells or levels";
    return std::nullopt;
}

std::vector<std::array<int64_t, 2>> water_grid_snap(const WaterGridDesc& desc, double eye_x,
                                                    double eye_z) {
    require_valid(desc);
    return snaps(desc, eye_x, eye_z);
}

WaterGrid water_grid(const WaterGridDesc& desc, double eye_x, double eye_z, GridTopology topology) {
    require_valid(desc);
    const auto snap = snaps(desc, eye_x, eye_z);
    const uint64_t n = desc.ring_cells;
    WaterGrid out;
    out.topology = topology;
    out.origin = frame_centre_of(eye_x, eye_z);
    out.patch_control_points = topology == GridTopology::Patches ? 4 : 0;
    out.morph_start = double(n / 2) + 4.0;
    out.morph_end = double(n) - 3.0;
    const uint64_t cells = 4 * n * n + uint64_t(desc.levels - 1) * 3 * n * n;
    out.vertices.reserve(water_grid_vertex_count(desc) * WaterGrid::kFloatsPerVertex);
    out.indices.reserve(cells * (topology == GridTopology::Patches ? 4 : 6));
    for (uint32_t k = desc.levels; k-- > 0;) {
        Level level{k, snap[k]};
        if (k > 0) {
            // c_{k-1} - c_k in h_k: s_{k-1} h_k - 2 s_k h_k, exactly, from the integers.
            level.has_hole = true;
            level.hole = {snap[k - 1][0] - 2 * snap[k][0], snap[k - 1][1] - 2 * snap[k][1]};
        }
        add_level(desc, level, eye_x, eye_z, out);
    }
    return out;
}

std::array<double, 2> water_grid_morphed(const WaterGrid& grid, uint32_t vertex, double eye_x,
                                         double eye_z) {
    if (vertex >= grid.vertex_count())
        throw std::out_of_range("water grid vertex " + std::to_string(vertex) + ": the grid has " +
                                std::to_string(grid.vertex_count()));
    const float* v = grid.vertices.data() + size_t(vertex) * WaterGrid::kFloatsPerVertex;
    const double x = v[0], z = v[1], h = v[4];
    const double ex = eye_x - grid.origin.x, ez = eye_z - grid.origin.z; // in the frame
    const double d = std::max(std::abs(x - ex), std::abs(z - ez)) / h;
    const double t =
        std::clamp((d - grid.morph_start) / (grid.morph_end - grid.morph_start), 0.0, 1.0);
    return {x + t * double(v[2]) + grid.origin.x, z + t * double(v[3]) + grid.origin.z};
}

} // namespace watergen
