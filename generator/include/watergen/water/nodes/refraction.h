// Refraction: the colour seen through the surface, before extinction (000 Toman, 002 Mihalik,
// 003 IceFall). The source is the lit scene itself (000: the frame buffer, no extra pass),
// sampled at a displaced screen uv. The catalog names the sampling-free parts
// ("refraction.screen_distort_uv", "refraction.refracted_ray_point",
// "refraction.refracted_ray_uv").
#pragma once

#include "watergen/ir/core/dsl.h"

namespace watergen {

// 000 / 003: uv + N.xz * refraction_distortion * saturate(depth / refraction_shore_fade_depth),
// clamped to [0, 1]. The fade keeps the shoreline (depth -> 0) from smearing dry land into
// the water (003's "artifacts along water edges"); a fade depth of 0 turns it off.
Expr screen_distort_uv(Graph& g, Expr uv, Expr normal, Expr depth);

// 002: W = U + dv R, R = refract(-V, N, n1 / n2), dv = clamp(depth, 0, refraction_dv_max) *
// refraction_dv_scale (the seed's clamp(dv, 0, 2) / 3: dv is the straight vertical length,
// too long for the bent ray). Under total internal reflection R = 0 and W = U.
// -V is `view_ray`. Full precision (positions).
Expr refracted_ray_point(Graph& g, Expr surface_point, Expr view_ray, Expr normal, Expr depth);

// 002: where W lands on the screen (projected with `refraction_view_proj_c0..c3`, the scene
// camera), clamped to [0, 1]; the undistorted `uv` under total internal reflection (no light
// crosses the surface) and when W is on or behind the camera plane (q.w <= 1e-4).
Expr refracted_ray_uv(Graph& g, Expr uv, Expr surface_point, Expr view_ray, Expr normal,
                      Expr depth);

} // namespace watergen
