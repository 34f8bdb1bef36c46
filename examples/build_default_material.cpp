// The default material written in C++ with MaterialBuilder instead of JSON
// (generator/plan/default_material.cpp), built for the scenes given on the command line, through
// the library alone. Writes exactly what
//   watergen build examples/materials/default.json --scene S... --out OUT
// writes (a test compares them byte for byte).
//
// Usage: build_default_material OUT SCENE.json...
#include <cstdio>

#include "watergen/pipeline/build/build_output.h"
#include "watergen/plan/material.h"
#include "watergen/plan/scene_file.h"

using namespace watergen;

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s OUT [SCENE.json ...]\n", argv[0]);
        return 2;
    }
    Diagnostics ds;
    BuildRequest request;
    request.material = default_material();
    for (int i = 2; i < argc && !has_errors(ds); ++i)
        if (auto scene = load_scene(argv[i], ds)) request.scenes.push_back(*scene);
    for (const auto& d : ds)
        std::fprintf(stderr, "%s\n", format_diagnostic(d).c_str());
    if (has_errors(ds)) return 2;
    request.out = argv[1];
    const BuildSummary summary = build_material(request);
    for (const auto& d : summary.diagnostics)
        std::fprintf(stderr, "%s\n", format_diagnostic(d).c_str());
    std::printf("%zu variants, %zu files -> %s\n", summary.variants, summary.files, argv[1]);
    return summary.ok() ? 0 : 1;
}
