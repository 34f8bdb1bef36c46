// A companion pass's pass.json as the runtime reads it (ShaderBuild::pass), under a manifest
// that lists it: whatever the bytes, pass() returns the pass or an error naming pass.json, and
// a pass it returns starts a UniformWriter whose values are the ones pass.json declares.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

#include "fuzz_build_dir.h"
#include "watergen/runtime/shader_build.h"
#include "watergen/runtime/uniform_writer.h"

namespace {

// The smallest manifest whose one variant has a caustics pass (the shape a permutations build
// writes; its values name the pass's parameters as a real one's do).
constexpr const char* kManifest = R"({
  "generator": "watergen 0.1.0", "mode": "permutations",
  "material": {"axes": {"caustics": ["area_ratio"]}}, "scenes": [{"name": "s"}],
  "variants": [{"scene": "s", "key": "caustics=area_ratio", "hash": "0123456789ab",
    "nodes": {"caustics": "caustics.area_ratio"}, "directory": "shaders/v", "files": {},
    "reflection": {},
    "passes": {"caustics": {"method": "area_ratio", "wave_model": "gerstner",
      "directory": "passes/caustics", "files": {"description": ["passes/caustics/pass.json"]},
      "draw": {"primitive": "triangles", "attribute": "grid_xz", "cells_per_texel": 2,
        "margin": {"parameter": "caustics_depth", "scale": 1.0, "add": 0.0},
        "window": "caustics_window", "texels": 64, "format": "R32_SFLOAT", "channel": "r",
        "clear": 0.0, "blend": "additive"},
      "values": {"caustics_depth": [3.0]}}}}]})";

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace watergen;
    static const fuzz::BuildDir dir("pass");
    static const bool written =
        (dir.write("manifest.json", kManifest, std::strlen(kManifest)), true);
    (void)written;
    static const ShaderBuild build = [] {
        std::string error;
        auto b = ShaderBuild::open(dir.path, &error);
        if (!b) std::abort(); // the fixed manifest must open
        return *b;
    }();
    dir.write("passes/caustics/pass.json", data, size);
    std::string error;
    const auto pass = build.pass(build.variants().front(), "caustics", &error);
    if (!pass) {
        if (error.rfind((dir.path / "passes/caustics/pass.json").string() + ": ", 0) != 0)
            std::abort();
        return 0;
    }
    const UniformWriter writer(pass->shader);
    for (const BlockParameter& p : pass->shader.parameters)
        if (!writer.has(p.name)) std::abort();
    return 0;
}
