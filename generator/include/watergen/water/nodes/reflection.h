// Reflection: what the surface mirrors (001 Lombard, 002 Mihalik, 003 IceFall).
// water-models.md "Reflection" has the formulas; the catalog names the sampling-free parts
// ("reflection.sky_lookup", "reflection.projective_uv", "reflection.fourier_series",
// "reflection.fourier_sky_weight", "reflection.fourier_horizon") so the probe can run them on
// the GPU (a compute shader has no implicit LOD, so the probe cannot sample).
#pragma once

#include <string>

#include "watergen/ir/core/dsl.h"

namespace watergen {

Parameter sky_color(); // constant sky (choice "none"), and the fallback of the others

// Texture inputs, by binding name (render/scene_optics_inputs.cpp makes the synthetic ones).
TextureInput sky_cube_texture();       // "sky_cube": environment cube, linear rgb
TextureInput reflection_map_texture(); // "reflection_map": the scene mirrored in the water plane
TextureInput fourier_coefs1_texture(); // "fourier_coefs1": a0, a1, b1, a2 per texel (003)
TextureInput fourier_coefs2_texture(); // "fourier_coefs2": b2, a3, b3, a4 per texel (003)

// 002: the reflection texture is rendered with the field of view extended by this factor
// (tan of the half angle x 1.5) so normal-displaced lookups find texels; the lookup divides
// the projected coordinates by it. The texture and the uniform must agree.
Parameter reflection_fov_extension();
// Where the Fourier coefficient textures lie on the water plane: uv = (xz - origin) / size.
Parameter fourier_map_origin();
Parameter fourier_map_size();

// Projective texturing (001): q = M p with M given as the vec4 columns `<prefix>_view_proj_c0..c3`
// (uniforms; uv orientation, v down, so that uv = 0.5 q.xy / q.w + 0.5), the result divided by
// `fov_scale` around the centre (002's FOV_ext; 1 for none) and clamped to [0, 1]. `valid` is
// false for q.w <= kMinProjectiveW (a point on or behind the camera plane, where the division
// mirrors or blows up); uv is then (0.5, 0.5). Computed in full precision.
constexpr double kMinProjectiveW = 1e-4;
struct ProjectiveUv {
    Expr uv;    // vec2
    Expr valid; // bool
};
ProjectiveUv projective_uv(Graph& g, Expr point, const std::string& prefix, const std::string& seed,
                           Expr fov_scale);

// 001 cube lookup: R = reflect(-V, N) with -V = view_ray; the lower hemisphere (R.y < 0) has
// no sky, so the lookup mirrors it into the upper half (001: "mirror the upper half of the
// cubemap down into the lower half") and returns the weight of 001's water tint,
// smoothstep(0, reflection_horizon_band, -R.y). Result vec4(direction, tint weight). A zero
// R (degenerate inputs) looks up the zenith.
Expr sky_cube_lookup(Graph& g, Expr view_ray, Expr normal);
// 001 + 002: uv of the planar reflection texture at the normal-displaced surface point
// P + d (N.x, 0, N.z); vec3(uv, valid ? 1 : 0).
Expr planar_reflection_uv(Graph& g, Expr surface_point, Expr normal);
// 003 EvaluateFourier, trig-free: the series a0 + a1 cos t + b1 sin t + a2 cos 2t + b2 sin 2t +
// a3 cos 3t + b3 sin 3t + a4 cos 4t at the azimuth t of the ray's horizontal part (x = R.x,
// y = R.z). It is the tangent of the horizon's elevation. A vertical ray has no azimuth (the
// seed normalises a zero 2-vector): it gets t = 0, harmless since its elevation is 90 degrees.
Expr fourier_series(Graph& g, Expr coefs1, Expr coefs2, Expr ray);
// 003: how much sky the ray sees, in [0, 1]: smoothstep over +-fourier_transition of
// sin(elevation - horizon) = (R.y - v |R.xz|) / sqrt(1 + v^2) for a unit ray, v = tan(horizon),
// a comparison of tangents without atan2 or a division by |R.xz| (003).
Expr fourier_sky_weight(Graph& g, Expr coefs1, Expr coefs2, Expr ray);
// 003: mix(fourier_below_color, sky_color, fourier_sky_weight): the choice's colour once the
// coefficients are sampled at the surface point ((xz - fourier_map_origin) / fourier_map_size).
Expr fourier_horizon_color(Graph& g, Expr coefs1, Expr coefs2, Expr ray);

} // namespace watergen
