// The numeric harness: a graph's outputs evaluated for many input tuples on the GPU (as a
// compute shader on the Vulkan runner) and on the CPU in double, float and half.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/ir/emit/emitter.h"
#include "watergen/runner/vulkan_runner.h"
#include "watergen/water/node_catalog.h"

namespace watergen {

struct ProbeRun {
    ProbeLayout layout;
    size_t tuples = 0;
    // tuples x layout.output_stride, tuple-major.
    std::vector<double> gpu, cpu_double, cpu_float, cpu_half;
    bool strict_half = false; // the GPU ran the relaxed nodes in 16-bit arithmetic
    double pipeline_ms = 0, dispatch_ms = 0;
    std::vector<std::string> validation_messages;
    Diagnostics diagnostics;
    std::string error;
    bool ok() const { return error.empty() && !has_errors(diagnostics); }
};

// `inputs` holds tuples x layout.input_stride values, tuple-major (cast to float for the GPU).
// `uniforms` override parameter defaults on both sides; `textures` (by TextureInput name) feed
// both sides, linearly filtered, clamped to edge: every texture the graph reads must be there.
// Derivatives pair tuples 4k..4k+3 as a 2x2 quad (emit_probe): a graph that uses them takes
// whole quads (a tuple count that is a multiple of 4). Cost: one toolchain run, one
// pipeline (JIT) and one dispatch, plus three CPU evaluations. `options.strict_half` runs the
// graph's relaxed nodes in 16-bit arithmetic on the GPU (needs shaderFloat16): `gpu` is then
// what cpu_half models.
ProbeRun run_probe(VulkanRunner& runner, const Graph& g, Language language,
                   const std::vector<double>& inputs,
                   const std::map<std::string, std::vector<double>>& uniforms = {},
                   const std::map<std::string, TextureData>& textures = {},
                   const EmitOptions& options = {});

// Whether the graph's live nodes take ddx / ddy (then the probe needs whole quads of tuples).
bool uses_derivatives(const Graph& g);

// The synthetic scene's textures (make_synthetic_scene(64, 64).textures: every TextureInput the
// catalog nodes read), made once: what `watergen probe` and the stress tests supply.
const std::map<std::string, TextureData>& probe_scene_textures();

// What `watergen probe` runs, read and checked before any device is touched.
struct ProbeInputs {
    Graph graph;                // probe_graph of the node
    ProbeLayout layout;         // probe_layout of the graph
    std::vector<double> tuples; // read from the CSV, layout.input_stride each
    std::map<std::string, std::vector<double>> params; // the --param overrides
};
// The node's graph, the tuples of the CSV file at `csv_path` (whole 2x2 quads when the node
// takes derivatives) and the parameter overrides, checked as check_probe_parameters does.
std::optional<ProbeInputs> prepare_probe(const CatalogNode& node, const std::string& csv_path,
                                         const std::vector<std::string>& param_specs,
                                         bool allow_out_of_range, std::string& error);

} // namespace watergen
