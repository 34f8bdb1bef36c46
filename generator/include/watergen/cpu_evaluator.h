// Evaluates a Graph on the CPU: the reference every GPU image and stress input is compared
// with. Double is the reference; Float rounds every intermediate to binary32; Half rounds the
// relaxed-precision nodes (mediump / min16float) to binary16 and the rest to binary32, as a GPU
// that runs mediump at 16 bits would (lavapipe runs it at 32).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "watergen/ir.h"

namespace watergen {

enum class EvalPrecision { Double, Float, Half };
const char* to_string(EvalPrecision p);

// Rounds to the nearest binary16 value (ties to even; overflow to infinity; subnormals kept).
double round_to_half(double v);
double round_to(double v, EvalPrecision p);

struct TextureView {
    uint32_t width = 0, height = 0;
    const float* rgba = nullptr; // RGBA32F, row 0 = v = 0
};

enum class Filter { Nearest, Linear }; // both clamp to edge, as the runner's sampler

struct EvalInputs {
    std::map<std::string, std::vector<double>> uniforms; // overrides of parameter defaults
    std::map<std::string, TextureView> textures;
    Filter filter = Filter::Linear;
    // Per-lane fragment inputs: name -> lanes x components, lane-major.
    std::map<std::string, std::vector<double>> varyings;
    size_t lanes = 0;
};

struct EvalResult {
    std::vector<double> values; // lanes x components, lane-major
    int components = 0;
    std::string error; // non-empty on failure (missing texture, ill-typed graph, ...)
    bool ok() const { return error.empty(); }
};

// Evaluates output `output` for every lane. Derivatives (ddx, ddy) treat lanes 4k..4k+3 as a
// 2x2 quad (x, y) = (0,0), (1,0), (0,1), (1,1), with per-row / per-column differences.
// Cost: live nodes x lanes; lanes are processed in blocks of 1024.
EvalResult evaluate(const Graph& g, const std::string& output, const EvalInputs& inputs, EvalPrecision precision);

// Evaluates a fullscreen fragment graph over width x height pixels with v_uv at pixel centres,
// like the runner's fullscreen triangle. Result is row-major, row 0 = top.
EvalResult evaluate_image(const Graph& g, const std::string& output, EvalInputs inputs, uint32_t width,
                          uint32_t height, EvalPrecision precision);

} // namespace watergen
