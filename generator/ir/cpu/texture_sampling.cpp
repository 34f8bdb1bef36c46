#include "texture_sampling.h"

#include <algorithm>
#include <cmath>

namespace watergen {

namespace {

double fetch(const TextureView& t, long x, long y, int c) {
    x = std::clamp<long>(x, 0, static_cast<long>(t.width) - 1);
    y = std::clamp<long>(y, 0, static_cast<long>(t.height) - 1);
    return t.rgba[(static_cast<size_t>(y) * t.width + static_cast<size_t>(x)) * 4 + c];
}

double cube_fetch(const TextureView& t, int face, long i, long j, int c) {
    const long n = static_cast<long>(t.width);
    i = std::clamp<long>(i, 0, n - 1);
    j = std::clamp<long>(j, 0, n - 1);
    return t.rgba[((static_cast<size_t>(face) * t.width + static_cast<size_t>(j)) * t.width +
                   static_cast<size_t>(i)) *
                      4 +
                  c];
}

// Texel (i, j) of `face`, where at most one of i, j lies one texel past the face: such a texel
// is the one across the edge on the adjacent face (Vulkan "Cube Map Edge Handling"). Its centre,
// pushed past the edge, points into exactly that texel of the neighbour (the nearest texel
// centre of the neighbour is half a texel away, the shrink towards the neighbour's centre is
// under half a texel), so the neighbour is found geometrically rather than from a table.
double cube_texel(const TextureView& t, int face, long i, long j, int c) {
    const long n = static_cast<long>(t.width);
    if (i >= 0 && i < n && j >= 0 && j < n) return cube_fetch(t, face, i, j, c);
    double d[3];
    cube_face_direction(face, (i + 0.5) / n, (j + 0.5) / n, d);
    const CubeFaceCoord a = cube_face_coord(d[0], d[1], d[2]);
    return cube_fetch(t, a.face, static_cast<long>(std::floor(a.s * n)),
                      static_cast<long>(std::floor(a.t * n)), c);
}

} // namespace

// Vulkan spec, texel filtering with clamp-to-edge: u' = u * width - 0.5 for linear.
void sample_2d(const TextureView& t, Filter filter, double u, double v, double out[4]) {
    if (!std::isfinite(u)) u = 0.0;
    if (!std::isfinite(v)) v = 0.0;
    u = std::clamp(u, -1.0, 2.0);
    v = std::clamp(v, -1.0, 2.0);
    if (filter == Filter::Nearest) {
        const long x = static_cast<long>(std::floor(u * t.width));
        const long y = static_cast<long>(std::floor(v * t.height));
        for (int c = 0; c < 4; ++c)
            out[c] = fetch(t, x, y, c);
        return;
    }
    const double fu = u * t.width - 0.5, fv = v * t.height - 0.5;
    const long x0 = static_cast<long>(std::floor(fu)), y0 = static_cast<long>(std::floor(fv));
    const double a = fu - std::floor(fu), b = fv - std::floor(fv);
    for (int c = 0; c < 4; ++c) {
        const double t00 = fetch(t, x0, y0, c), t10 = fetch(t, x0 + 1, y0, c);
        const double t01 = fetch(t, x0, y0 + 1, c), t11 = fetch(t, x0 + 1, y0 + 1, c);
        out[c] = (1 - a) * (1 - b) * t00 + a * (1 - b) * t10 + (1 - a) * b * t01 + a * b * t11;
    }
}

void sample_cube(const TextureView& t, Filter filter, double x, double y, double z, double out[4]) {
    const CubeFaceCoord f = cube_face_coord(x, y, z);
    const double n = t.width;
    if (filter == Filter::Nearest) {
        // Vulkan: nearest filtering of a cube clamps to the edge of the selected face.
        for (int c = 0; c < 4; ++c)
            out[c] = cube_fetch(t, f.face, static_cast<long>(std::floor(f.s * n)),
                                static_cast<long>(std::floor(f.t * n)), c);
        return;
    }
    const double fu = f.s * n - 0.5, fv = f.t * n - 0.5;
    const long x0 = static_cast<long>(std::floor(fu)), y0 = static_cast<long>(std::floor(fv));
    const double a = fu - std::floor(fu), b = fv - std::floor(fv);
    const long size = static_cast<long>(t.width);
    auto outside = [size](long k) { return k < 0 || k >= size; };
    for (int c = 0; c < 4; ++c) {
        double texel[2][2];
        int corner_i = -1, corner_j = -1;
        for (int dj = 0; dj < 2; ++dj)
            for (int di = 0; di < 2; ++di) {
                if (outside(x0 + di) && outside(y0 + dj)) {
                    // Past both edges: no face owns it (at most one per footprint).
                    corner_i = di, corner_j = dj;
                    texel[dj][di] = 0.0;
                    continue;
                }
                texel[dj][di] = cube_texel(t, f.face, x0 + di, y0 + dj, c);
            }
        if (corner_i >= 0) {
            // The mean of the three texels that do exist (lavapipe: the corner's weight is
            // shared equally among the other three).
            const double sum = texel[0][0] + texel[0][1] + texel[1][0] + texel[1][1];
            texel[corner_j][corner_i] = sum / 3.0;
        }
        out[c] = (1 - a) * (1 - b) * texel[0][0] + a * (1 - b) * texel[0][1] +
                 (1 - a) * b * texel[1][0] + a * b * texel[1][1];
    }
}

CubeFaceCoord cube_face_coord(double x, double y, double z) {
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return {};
    const double ax = std::fabs(x), ay = std::fabs(y), az = std::fabs(z);
    // Vulkan "Cube Map Face Selection": (sc, tc, rc) per major axis; s = (sc / |rc| + 1) / 2.
    int face = 0;
    double sc = 0, tc = 0, ma = 0;
    if (az >= std::max(ax, ay)) {
        ma = az;
        face = std::signbit(z) ? 5 : 4;
        sc = std::signbit(z) ? -x : x;
        tc = -y;
    } else if (ax > ay) {
        ma = ax;
        face = std::signbit(x) ? 1 : 0;
        sc = std::signbit(x) ? z : -z;
        tc = -y;
    } else {
        ma = ay;
        face = std::signbit(y) ? 3 : 2;
        sc = x;
        tc = std::signbit(y) ? -z : z;
    }
    const double half_inverse = ma > 0 ? 0.5 / ma : 0.0; // zero vector: the face centre
    return {face, sc * half_inverse + 0.5, tc * half_inverse + 0.5};
}

void cube_face_direction(int face, double s, double t, double d[3]) {
    const double sc = 2.0 * s - 1.0, tc = 2.0 * t - 1.0;
    switch (face) { // the table of cube_face_coord, solved for the direction
    case 0:
        d[0] = 1, d[1] = -tc, d[2] = -sc;
        return; // +X: sc = -z, tc = -y
    case 1:
        d[0] = -1, d[1] = -tc, d[2] = sc;
        return; // -X: sc = +z, tc = -y
    case 2:
        d[0] = sc, d[1] = 1, d[2] = tc;
        return; // +Y: sc = +x, tc = +z
    case 3:
        d[0] = sc, d[1] = -1, d[2] = -tc;
        return; // -Y: sc = +x, tc = -z
    case 4:
        d[0] = sc, d[1] = -tc, d[2] = 1;
        return; // +Z: sc = +x, tc = -y
    default:
        d[0] = -sc, d[1] = -tc, d[2] = -1;
        return; // -Z: sc = -x, tc = -y
    }
}

} // namespace watergen
