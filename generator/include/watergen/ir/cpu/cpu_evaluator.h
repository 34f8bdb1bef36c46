// Evaluates a Graph on the CPU: the reference every GPU image and stress input is compared
// with. Double is the reference; Float rounds every intermediate to binary32; Half rounds the
// relaxed-precision nodes (mediump / min16float) to binary16 and the rest to binary32, as a GPU
// that runs mediump at 16 bits would (lavapipe runs it at 32).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "watergen/ir/core/ir.h"
#include "watergen/runtime/host_values.h"

namespace watergen {

enum class EvalPrecision { Double, Float, Half };
const char* to_string(EvalPrecision p);

// Rounds to the nearest binary16 value (ties to even; overflow to infinity; subnormals kept).
double round_to_half(double v);
// Rounds to the binary16 value nearest to v that is not farther from zero than v (65504 for
// finite values beyond it).
double round_to_half_toward_zero(double v);
double round_to(double v, EvalPrecision p);
// Distance in binary16 steps between two binary16 values (0 when equal, +0 and -0 equal; 1 from
// 65504 to infinity); -1 when either is NaN. Values that are not binary16 are rounded first.
int64_t half_ulp_distance(double a, double b);

// How closely values computed in binary16 (GPU strict half) agree with their model (the CPU's
// half mode), over pairs finite on both sides.
struct HalfAgreement {
    uint64_t values = 0, equal = 0, within_1 = 0; // compared; 0 and at most 1 ulp apart
    int64_t max_ulps = 0;
    size_t max_index = 0; // the caller's index of the first pair max_ulps apart
    void add(double test, double reference, size_t index);
};

// RGBA32F texels laid out like the runner's TextureData: layer-major, then rows (row 0 = v = 0),
// then columns. A cube holds 6 square faces in Vulkan order +X, -X, +Y, -Y, +Z, -Z.
struct TextureView {
    uint32_t width = 0, height = 0;
    const float* rgba = nullptr;
    // 1 (2D) or 6 (cube); 0 = as the sampled binding's type needs (2D: 1, cube: 6).
    uint32_t layers = 0;
};

// Both clamp to edge, as the runner's sampler. Cubes follow Vulkan: the face is picked by the
// major axis of the direction ("Cube Map Face Selection"); linear filtering is seamless, taking
// texels past a face edge from the adjacent face and replacing the missing corner texel by the
// mean of the other three (what lavapipe does); nearest clamps within the face.
enum class Filter { Nearest, Linear };

// Vulkan's cube face selection for direction (x, y, z): face index in Vulkan order and the
// face coordinates (s, t) in [0, 1]. Ties pick z over y over x (lavapipe's order); a zero or
// non-finite direction samples the centre of +Z.
struct CubeFaceCoord {
    int face = 4;
    double s = 0.5, t = 0.5;
};
CubeFaceCoord cube_face_coord(double x, double y, double z);
// The inverse: the (unnormalised) direction through face coordinates (s, t) of `face`; also
// defined past the face's edges (s, t outside [0, 1]). For making cube textures.
void cube_face_direction(int face, double s, double t, double direction[3]);

// The float model's rounding, applied inside a double evaluation (EvalPrecision::Double only,
// ignored otherwise) to find out where a float result's error comes from and how large it can
// be: at the operations [round_first, round_end) (indices into evaluation_sites()), results
// rounded to binary32 as the float evaluation rounds them; and at every operation, results
// moved by a pseudo-random relative amount in [-relative, relative], the same for the same
// seed, lane, operation and loop iteration (so a result does not depend on threads or blocks).
struct FloatPerturbation {
    int64_t round_first = 0, round_end = 0;
    uint64_t seed = 0;
    double relative = 0; // 0: none
    bool active() const { return round_end > round_first || relative > 0; }
};

struct EvalInputs {
    std::map<std::string, std::vector<double>> uniforms; // overrides of parameter defaults
    // The frame the host rules move positions into (ir/core/shader_values.h); by default the
    // eye's. A companion pass takes its water pass' centre.
    std::optional<FrameCentre> frame_centre;
    std::map<std::string, TextureView> textures;
    Filter filter = Filter::Linear;
    // Per-lane fragment inputs: name -> lanes x components, lane-major.
    std::map<std::string, std::vector<double>> varyings;
    size_t lanes = 0;
    // Threads sharing the blocks of lanes; 0 = one per core. Results do not depend on it.
    unsigned threads = 0;
    FloatPerturbation perturbation;
};

struct EvalResult {
    std::vector<double> values; // lanes x components, lane-major
    int components = 0;
    std::string error; // non-empty on failure (missing texture, ill-typed graph, ...)
    bool ok() const { return error.empty(); }
};

// Evaluates output `output` for every lane. Derivatives (ddx, ddy) treat lanes 4k..4k+3 as a
// 2x2 quad (x, y) = (0,0), (1,0), (0,1), (1,1), with per-row / per-column differences.
// The graph is compiled once per call into a flat program (a kernel per node, values stored
// structure-of-arrays: generator/ir/cpu/block_program.h) run over blocks of 256 lanes shared out to
// inputs.threads threads; nodes that are the same on every lane (parameters and what follows
// from them alone) are computed once, or once per loop iteration. A switch runs the case its
// selector (built from parameters and constants) picks: the program holds that case alone, so
// only its inputs must be supplied. About 0.45 s per 1024x1024 image for the Gerstner gold
// variant in float on this project's 2-core machine (watergen bench cpu). When an input is
// missing or malformed, no block is evaluated and `error` names the first failing node in node
// order.
EvalResult evaluate(const Graph& g, const std::string& output, const EvalInputs& inputs,
                    EvalPrecision precision);

// An operation of the evaluation (a node of the graph or of a loop body or switch case, in the
// order the evaluator runs them): the feature node that made it (Node::origin), its name, its
// operation.
struct EvalSite {
    std::string origin, name;
    Op op = Op::Constant;
    std::string operands; // its arguments, by name or else operation: "fract, -"
};
// The operations that compute values in the double evaluation of `output`, indexed as
// FloatPerturbation::site counts them. Empty when the graph has no such output.
std::vector<EvalSite> evaluation_sites(const Graph& g, const std::string& output,
                                       const EvalInputs& inputs);

// Evaluates a fullscreen fragment graph over width x height pixels with v_uv at pixel centres,
// like the runner's fullscreen triangle. Result is row-major, row 0 = top.
EvalResult evaluate_image(const Graph& g, const std::string& output, EvalInputs inputs,
                          uint32_t width, uint32_t height, EvalPrecision precision);

} // namespace watergen
