// The built-in default material, and the example of MaterialBuilder in C++: the same material as
// examples/materials/default.json (a test builds both and compares them), used by
// `watergen build` without a material file and by examples/build_default_material.cpp.
#include "watergen/plan/material.h"

namespace watergen {

Material default_material() {
    Diagnostics ds;
    auto m =
        MaterialBuilder("default")
            .description("clear sea water: a few choices per axis, enough for every example scene "
                         "to prune something")
            .preset("tropical_ocean")
            .offer("fresnel", {"schlick", "exact"})
            .offer("extinction", {"absorb_scatter"})
            .offer("specular", {"none", "blinn_phong"})
            .offer("foam", {"none", "shore"})
            .offer("reflection", {"sky_cubemap", "planar_projective"})
            .offer("refraction", {"screen_distort"})
            .offer("normals", {"flat"})
            .offer("waves", {"flat", "gerstner"})
            .offer("shore", {"hard", "soft"})
            .offer("precision", {"full", "half"})
            .offer("caustics", {"none", "area_ratio"})
            .excludes_choice("precision", "half", "fresnel", {"exact"},
                             "the exact Fresnel term is the reference; mobile builds use Schlick")
            .parameter("absorb_coefficients", {0.46, 0.09, 0.06})
            .range("absorb_coefficients", 0.05, 2.0)
            .range("scatter_coefficient", 0.01, 2.0)
            .parameter("shore_hardness", {1.0})
            .range("shore_hardness", 0.5, 4.0)
            .targets({"glsl", "hlsl", "spirv", "glsl330", "essl300", "msl", "reflection"})
            .build(ds);
    return *m; // the built-in description is valid by construction (tested)
}

} // namespace watergen
