// The default material written in C++ with MaterialBuilder instead of JSON, built for the
// scenes given on the command line. Writes exactly what
//   watergen build examples/materials/default.json --scene S... --out OUT
// writes (a test compares them byte for byte).
//
// Usage: build_default_material OUT SCENE.json...
#include <cstdio>

#include "watergen/pipeline/build_output.h"
#include "watergen/plan/material.h"
#include "watergen/plan/scene_file.h"

using namespace watergen;

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s OUT [SCENE.json ...]\n", argv[0]);
        return 2;
    }
    Diagnostics ds;
    auto material = MaterialBuilder("default")
                        .description("clear sea water: a few choices per axis, enough for every example scene to prune something")
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
                        .excludes_choice("precision", "half", "fresnel", {"exact"},
                                         "the exact Fresnel term is the reference; mobile builds use Schlick")
                        .parameter("absorb_coefficients", {0.46, 0.09, 0.06})
                        .range("absorb_coefficients", 0.05, 2.0)
                        .range("scatter_coefficient", 0.01, 2.0)
                        .parameter("shore_hardness", {1.0})
                        .range("shore_hardness", 0.5, 4.0)
                        .targets({"glsl", "hlsl", "spirv", "glsl330", "essl300", "msl", "reflection"})
                        .build(ds);
    BuildRequest request;
    if (material) request.material = *material;
    for (int i = 2; i < argc && !has_errors(ds); ++i)
        if (auto scene = load_scene(argv[i], ds)) request.scenes.push_back(*scene);
    for (const auto& d : ds) std::fprintf(stderr, "%s\n", format_diagnostic(d).c_str());
    if (has_errors(ds)) return 2;
    request.out = argv[1];
    const BuildSummary summary = build_material(request);
    for (const auto& d : summary.diagnostics) std::fprintf(stderr, "%s\n", format_diagnostic(d).c_str());
    std::printf("%zu variants, %zu files -> %s\n", summary.variants, summary.files, argv[1]);
    return summary.ok() ? 0 : 1;
}
