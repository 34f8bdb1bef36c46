// Inputs of the reflection and refraction nodes for the synthetic scene: the sky cube, the
// planar reflection map, the Fourier horizon coefficients and the camera matrices. Every
// texture is a smooth function of direction or position, evaluated at texel centres:
// deterministic, no noise.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include <glm/glm.hpp>

#include "scene_geometry.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/water/nodes/reflection.h"

namespace watergen {

namespace {

using glm::dvec3;
using scene_geometry::kPi;
using scene_geometry::sphere_entry;
using scene_geometry::sunlit;
using scene_geometry::unplaced;

constexpr uint32_t kSkyFaceSize = 32;
constexpr uint32_t kFourierSize = 16;

// The scene's geometry as synthetic_scene.h documents it (its tracer is private to
// synthetic_scene.cpp): the seabed plane y = 2 - 0.25 (z + 12), dry above the water level.
const dvec3 kSeabedNormal{0.0, 1.0, 0.25}; // n . p = -1 on the seabed
constexpr double kSeabedOffset = -1.0;
const dvec3 kSandAlbedo{0.71, 0.63, 0.46};

double seabed_height(double z) {
    return kSeabedOffset - kSeabedNormal.z * z;
}

dvec3 uniform_vec3(const SyntheticScene& scene, const char* name, dvec3 fallback) {
    auto it = scene.uniforms.find(name);
    if (it == scene.uniforms.end() || it->second.size() != 3) return fallback;
    return {it->second[0], it->second[1], it->second[2]};
}

double uniform_float(const SyntheticScene& scene, const char* name, double fallback) {
    auto it = scene.uniforms.find(name);
    return it == scene.uniforms.end() || it->second.size() != 1 ? fallback : it->second[0];
}

// The scene's value of a parameter the textures depend on, else the parameter's default.
std::vector<double> scene_value(const SyntheticScene& scene, const Parameter& p) {
    auto it = scene.uniforms.find(p.name);
    return it == scene.uniforms.end() || it->second.size() != p.default_value.size()
               ? p.default_value
               : it->second;
}

double smooth01(double x) {
    x = std::clamp(x, 0.0, 1.0);
    return x * x * (3.0 - 2.0 * x);
}

// Sky radiance along a unit direction: horizon haze to zenith blue (quadratic in elevation, so
// no kink above the horizon), a hazy ground colour below, and a glow around the sun.
dvec3 sky_radiance(const dvec3& d, const dvec3& to_sun) {
    const double up = std::max(d.y, 0.0);
    const dvec3 horizon{0.80, 0.85, 0.90}, zenith{0.25, 0.45, 0.80}, ground{0.36, 0.34, 0.30};
    dvec3 c = glm::mix(horizon, zenith, up * (2.0 - up));
    c = glm::mix(c, ground, smooth01(-d.y / 0.2));
    const double s = std::max(glm::dot(d, to_sun), 0.0);
    return c + dvec3{1.0, 0.9, 0.7} * (0.6 * std::pow(s, 64.0) + 0.15 * std::pow(s, 4.0));
}

dvec3 lit_sand(const dvec3& to_sun) {
    return sunlit(kSandAlbedo, glm::normalize(kSeabedNormal), to_sun);
}

void put(TextureData& t, size_t texel, const dvec3& c, double a = 1.0) {
    for (int k = 0; k < 3; ++k)
        t.rgba[texel * 4 + k] = static_cast<float>(c[k]);
    t.rgba[texel * 4 + 3] = static_cast<float>(a);
}

TextureData make_sky_cube(const dvec3& to_sun) {
    TextureData t{kSkyFaceSize, kSkyFaceSize, 6,
                  std::vector<float>(size_t(kSkyFaceSize) * kSkyFaceSize * 6 * 4)};
    for (int face = 0; face < 6; ++face)
        for (uint32_t y = 0; y < kSkyFaceSize; ++y)
            for (uint32_t x = 0; x < kSkyFaceSize; ++x) {
                double d[3];
                cube_face_direction(face, (x + 0.5) / kSkyFaceSize, (y + 0.5) / kSkyFaceSize, d);
                const size_t texel = (size_t(face) * kSkyFaceSize + y) * kSkyFaceSize + x;
                put(t, texel, sky_radiance(glm::normalize(dvec3{d[0], d[1], d[2]}), to_sun));
            }
    return t;
}

struct Camera {
    dvec3 eye, forward, right, up;
    double tan_half_fov_y, aspect;
};

// View-projection columns in uv orientation: uv = 0.5 q.xy / q.w + 0.5 with v down, q.w the
// distance in front of the camera (projective_uv in nodes/reflection.h).
void set_view_proj(SyntheticScene& scene, const std::string& prefix, const Camera& c) {
    const dvec3 row_x = c.right / (c.tan_half_fov_y * c.aspect), row_y = -c.up / c.tan_half_fov_y,
                row_w = c.forward;
    for (int k = 0; k < 3; ++k)
        scene.uniforms[prefix + "_view_proj_c" + std::to_string(k)] = {row_x[k], row_y[k], 0.0,
                                                                       row_w[k]};
    scene.uniforms[prefix + "_view_proj_c3"] = {-glm::dot(row_x, c.eye), -glm::dot(row_y, c.eye),
                                                0.0, -glm::dot(row_w, c.eye)};
}

// The world of the mirrored camera: water level, sun, the view's standing sphere.
struct MirroredScene {
    double level;
    dvec3 to_sun;
    std::optional<StandingSphere> sphere;
};

// What the mirrored camera sees with the water plane as its clip plane (001, 002): only the
// part of a ray above the water counts. Over dry land the ray leaves the plane inside the beach
// and sees sand; over water it sees what lies above (the beach where the ray rises towards it,
// the view's standing sphere if any; the other sphere is submerged) and then the sky.
dvec3 mirrored_view(const dvec3& origin, const dvec3& d, const MirroredScene& scene) {
    const dvec3& to_sun = scene.to_sun;
    if (d.y <= 0.0) return sky_radiance(d, to_sun); // never rises above the water
    const dvec3 p = origin + d * ((scene.level - origin.y) / d.y);
    if (seabed_height(p.z) > scene.level) return lit_sand(to_sun);
    double sand = -1.0;
    const double facing = glm::dot(kSeabedNormal, d);
    if (facing < 0.0) sand = (kSeabedOffset - glm::dot(kSeabedNormal, p)) / facing;
    if (scene.sphere) {
        const dvec3 centre{scene.sphere->centre[0], scene.sphere->centre[1],
                           scene.sphere->centre[2]};
        const std::optional<double> t = sphere_entry(p, d, centre, scene.sphere->radius);
        if (t && (sand <= 0.0 || *t < sand)) {
            const StandingSphere& s = *scene.sphere;
            // t = 0 where the sphere stands in the water at p: shaded with p's normal.
            return sunlit({s.albedo[0], s.albedo[1], s.albedo[2]},
                          glm::normalize(p + d * *t - centre), to_sun);
        }
    }
    if (sand > 0.0) return lit_sand(to_sun);
    return sky_radiance(d, to_sun);
}

TextureData make_reflection_map(uint32_t width, uint32_t height, const Camera& mirrored,
                                double fov_extension, const MirroredScene& scene) {
    TextureData t{width, height, 1, std::vector<float>(size_t(width) * height * 4)};
    const double sx_scale = mirrored.tan_half_fov_y * mirrored.aspect * fov_extension;
    const double sy_scale = mirrored.tan_half_fov_y * fov_extension;
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            // Texel centre -> direction: the inverse of set_view_proj's uv with the extended FOV.
            const double nx = 2.0 * (x + 0.5) / width - 1.0, ny = 2.0 * (y + 0.5) / height - 1.0;
            const dvec3 d = glm::normalize(mirrored.forward + mirrored.right * (nx * sx_scale) -
                                           mirrored.up * (ny * sy_scale));
            put(t, size_t(y) * width + x, mirrored_view(mirrored.eye, d, scene));
        }
    return t;
}
// Tangent of the horizon's elevation seen from (x, level, z) towards azimuth `a` (direction
// (cos a, sin a) in xz): the beach rising towards -z at the seabed's slope 0.25 (its asymptote
// for a distant eye), or a ridge of hills 300 m across the bay, 25 +- 10 m high.
double horizon_tangent(double x, double z, double a) {
    const double c = std::cos(a), s = std::sin(a);
    const double beach = kSeabedNormal.z * std::max(-s, 0.0);
    double ridge = 0.0;
    if (s > 1e-3) {
        const double distance = (300.0 - z) / s;
        ridge = (25.0 + 10.0 * std::sin((x + distance * c) / 60.0)) / distance;
    }
    return std::max(beach, ridge);
}

// 003: eight Fourier coefficients of the horizon per texel (a0, a1, b1, a2 | b2, a3, b3, a4),
// projected by numerical integration over the azimuth. `origin` is in the world: the horizon
// (the beach, the ridge) is the scene's, around the origin moved by the world offset.
void make_fourier_maps(SyntheticScene& scene, const std::vector<double>& world_origin,
                       const std::vector<double>& size) {
    const std::array<double, 3>& offset = scene.view.world_offset;
    const double origin[2] = {unplaced(world_origin[0], offset[0]),
                              unplaced(world_origin[1], offset[2])};
    TextureData c1{kFourierSize, kFourierSize, 1,
                   std::vector<float>(size_t(kFourierSize) * kFourierSize * 4)};
    TextureData c2 = c1;
    constexpr int kSteps = 720;
    for (uint32_t j = 0; j < kFourierSize; ++j)
        for (uint32_t i = 0; i < kFourierSize; ++i) {
            const double x = origin[0] + size[0] * (i + 0.5) / kFourierSize;
            const double z = origin[1] + size[1] * (j + 0.5) / kFourierSize;
            double a[5] = {}, b[5] = {};
            for (int k = 0; k < kSteps; ++k) {
                const double t = 2.0 * kPi * (k + 0.5) / kSteps, f = horizon_tangent(x, z, t);
                for (int n = 0; n <= 4; ++n) {
                    a[n] += f * std::cos(n * t);
                    b[n] += f * std::sin(n * t);
                }
            }
            a[0] /= kSteps;
            for (int n = 1; n <= 4; ++n)
                a[n] *= 2.0 / kSteps, b[n] *= 2.0 / kSteps;
            const size_t texel = size_t(j) * kFourierSize + i;
            put(c1, texel, {a[0], a[1], b[1]}, a[2]);
            put(c2, texel, {b[2], a[3], b[3]}, a[4]);
        }
    scene.textures["fourier_coefs1"] = std::move(c1);
    scene.textures["fourier_coefs2"] = std::move(c2);
}

} // namespace

void add_optics_inputs(SyntheticScene& scene) {
    const SceneCamera sc = scene_camera(scene.view, scene.width, scene.height);
    const Camera camera{{sc.eye[0], sc.eye[1], sc.eye[2]},
                        {sc.forward[0], sc.forward[1], sc.forward[2]},
                        {sc.right[0], sc.right[1], sc.right[2]},
                        {sc.up[0], sc.up[1], sc.up[2]},
                        sc.tan_half_fov_y,
                        sc.aspect};
    const std::array<double, 3>& offset = scene.view.world_offset;
    const double level = uniform_float(scene, "water_level", 0.0);
    const dvec3 to_sun =
        -glm::normalize(uniform_vec3(scene, "sun_direction", {-0.35, -0.75, 0.55}));

    // Refraction samples the scene colour where the main camera sees W.
    set_view_proj(scene, "refraction", camera);
    // The planar reflection camera: the eye mirrored in y = level, upside down (002, Fig. 3);
    // right stays, so the mirror image is not flipped left to right.
    auto mirror = [](dvec3 v) { return dvec3{v.x, -v.y, v.z}; };
    Camera mirrored = camera;
    mirrored.eye = {camera.eye.x, 2.0 * level - camera.eye.y, camera.eye.z};
    mirrored.forward = mirror(camera.forward);
    mirrored.up = mirror(camera.up);
    set_view_proj(scene, "reflection", mirrored);

    // Textures and the uniforms that locate them agree: made for the scene's values. The
    // matrices above are the world's; the reflection map is traced around the origin (the
    // scene's own frame, scene_views.h), where its geometry is defined.
    const double fov_extension = scene_value(scene, reflection_fov_extension())[0];
    const double local_level = unplaced(level, offset[1]);
    Camera local_mirrored = mirrored;
    local_mirrored.eye = {scene.view.eye[0], 2.0 * local_level - scene.view.eye[1],
                          scene.view.eye[2]};
    scene.textures["reflection_map"] =
        make_reflection_map(scene.width, scene.height, local_mirrored, fov_extension,
                            {local_level, to_sun, scene.view.standing_sphere});
    scene.textures["sky_cube"] = make_sky_cube(to_sun);
    make_fourier_maps(scene, scene_value(scene, fourier_map_origin()),
                      scene_value(scene, fourier_map_size()));
}

} // namespace watergen
