#include "watergen/eval/probe/probe.h"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>

#include "watergen/eval/probe/probe_table.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/toolchain/toolchain.h"

namespace watergen {

namespace {

std::string binding_name(const Reflection& r, uint32_t set, uint32_t binding) {
    for (const auto& b : r.bindings)
        if (b.set == set && b.binding == binding) return b.name;
    return "";
}

// The textures the shader reads, taken from `supplied`; an error names the first one missing.
bool pick_textures(const ShaderInterface& interface,
                   const std::map<std::string, TextureData>& supplied,
                   std::map<std::string, TextureData>& picked, std::string& error) {
    for (const auto& t : interface.textures) {
        auto it = supplied.find(t.name);
        if (it == supplied.end()) {
            error = "the graph reads texture '" + t.name + "'; none supplied";
            return false;
        }
        picked.emplace(t.name, it->second);
    }
    return true;
}

// Runs the compiled probe over every tuple, in dispatches of at most 65535 workgroups.
void run_on_gpu(VulkanRunner& runner, const ToolchainOutputs& built, uint32_t set, ComputeJob& job,
                const std::vector<double>& inputs, ProbeRun& run) {
    const uint32_t in_stride = run.layout.input_stride, out_stride = run.layout.output_stride;
    job.spirv = built.spirv_optimized;
    job.reflection = built.reflection;
    const std::string in_name = binding_name(built.reflection, set, kProbeInputBinding);
    const std::string out_name = binding_name(built.reflection, set, kProbeOutputBinding);
    runner.clear_validation_messages();
    run.gpu.resize(run.tuples * out_stride);
    // Vulkan guarantees 65535 workgroups per dispatch dimension; larger inputs run in chunks
    // (of whole quads, so ddx / ddy pair the same tuples as on the CPU).
    const size_t chunk_tuples = size_t{65535} * kProbeWorkgroupSize;
    for (size_t first = 0; first < run.tuples; first += chunk_tuples) {
        const size_t count = std::min(chunk_tuples, run.tuples - first);
        // Pad to whole workgroups by repeating the chunk's last tuple; padded results are dropped
        // (and padded quads are whole quads of their own: the tuples are whole quads).
        const size_t groups = (count + kProbeWorkgroupSize - 1) / kProbeWorkgroupSize;
        const size_t padded = groups * kProbeWorkgroupSize;
        std::vector<float> in_floats(padded * in_stride);
        for (size_t t = 0; t < padded; ++t)
            for (uint32_t k = 0; k < in_stride; ++k)
                in_floats[t * in_stride + k] =
                    static_cast<float>(inputs[(first + std::min(t, count - 1)) * in_stride + k]);
        std::vector<uint8_t> in_bytes(in_floats.size() * 4);
        std::memcpy(in_bytes.data(), in_floats.data(), in_bytes.size());
        job.buffers[in_name] = std::move(in_bytes);
        job.output_sizes[out_name] = padded * out_stride * 4;
        job.group_count_x = static_cast<uint32_t>(groups);
        const ComputeResult result = runner.run_compute(job);
        if (!result.ok) {
            run.validation_messages = runner.validation_messages();
            run.error = result.error;
            return;
        }
        run.pipeline_ms += result.pipeline_ms;
        run.dispatch_ms += result.dispatch_ms;
        const auto& out_bytes = result.buffers.at(out_name);
        for (size_t i = 0; i < count * out_stride; ++i) {
            float f;
            std::memcpy(&f, out_bytes.data() + i * 4, 4);
            run.gpu[first * out_stride + i] = f;
        }
    }
    run.validation_messages = runner.validation_messages();
}

// The same tuples, uniforms and textures on the CPU evaluator in double, float and half.
void run_on_cpu(const Graph& g, const std::vector<double>& inputs,
                const std::map<std::string, std::vector<double>>& uniforms,
                const std::map<std::string, TextureData>& textures, ProbeRun& run) {
    const uint32_t in_stride = run.layout.input_stride, out_stride = run.layout.output_stride;
    EvalInputs eval;
    eval.uniforms = uniforms;
    eval.textures = texture_views(textures);
    eval.filter = Filter::Linear;
    eval.lanes = run.tuples;
    for (const auto& field : run.layout.inputs) {
        const int n = component_count(field.type);
        auto& v = eval.varyings[field.name];
        for (size_t t = 0; t < run.tuples; ++t)
            for (int c = 0; c < n; ++c)
                v.push_back(inputs[t * in_stride + field.offset + static_cast<uint32_t>(c)]);
    }
    for (auto [precision, target] : {std::pair{EvalPrecision::Double, &run.cpu_double},
                                     std::pair{EvalPrecision::Float, &run.cpu_float},
                                     std::pair{EvalPrecision::Half, &run.cpu_half}}) {
        target->assign(run.tuples * out_stride, 0.0);
        for (const auto& field : run.layout.outputs) {
            const EvalResult r = evaluate(g, field.name, eval, precision);
            if (!r.ok()) {
                run.error = "CPU evaluator: " + r.error;
                return;
            }
            for (size_t t = 0; t < run.tuples; ++t)
                for (int c = 0; c < r.components; ++c)
                    (*target)[t * out_stride + field.offset + static_cast<uint32_t>(c)] =
                        r.values[t * r.components + c];
        }
    }
}

} // namespace

ProbeRun run_probe(VulkanRunner& runner, const Graph& g, Language language,
                   const std::vector<double>& inputs,
                   const std::map<std::string, std::vector<double>>& uniforms,
                   const std::map<std::string, TextureData>& textures, const EmitOptions& options) {
    ProbeRun run;
    run.strict_half = options.strict_half;
    run.diagnostics = g.diagnostics();
    if (has_errors(run.diagnostics)) return run;
    run.layout = probe_layout(g);
    const uint32_t in_stride = run.layout.input_stride;
    if (in_stride == 0 || inputs.size() % in_stride != 0) {
        run.error = "input holds " + std::to_string(inputs.size()) +
                    " values, not a whole number of " + std::to_string(in_stride) + "-value tuples";
        return run;
    }
    run.tuples = inputs.size() / in_stride;
    if (run.tuples == 0) {
        run.error = "no input tuples";
        return run;
    }

    if (uses_derivatives(g) && run.tuples % 4 != 0) {
        run.error = "the graph takes ddx / ddy over quads of tuples 4k..4k+3; " +
                    std::to_string(run.tuples) + " tuples are not whole quads";
        return run;
    }

    const std::string file = std::string("probe.") + file_extension(language, ShaderStage::Compute);
    const EmittedShader shader = emit_probe(g, language, file, "probe", run.diagnostics, options);
    if (has_errors(run.diagnostics)) return run;
    ComputeJob job;
    if (!pick_textures(shader.interface, textures, job.textures, run.error)) return run;
    CompileRequest request{language == Language::Glsl ? SourceLanguage::Glsl : SourceLanguage::Hlsl,
                           ShaderStage::Compute, shader.source, file, "main"};
    request.hlsl_16bit_types = options.strict_half;
    const ToolchainOutputs built = run_toolchain(request);
    Diagnostics ds;
    for (const auto& d : built.diagnostics)
        if (d.severity != Severity::Note)
            ds.push_back(d); // e.g. "no compute in GLSL 330": expected here
    attribute_to_nodes(shader, ds);
    run.diagnostics.insert(run.diagnostics.end(), ds.begin(), ds.end());
    if (!built.ok()) return run;

    job.uniforms = pack_uniforms(shader.interface.uniforms, shader.interface.parameters, uniforms);
    job.specialization = specialization_values(shader.interface.specialization, uniforms);
    run_on_gpu(runner, built, probe_set(shader.interface), job, inputs, run);
    if (!run.error.empty()) return run;
    run_on_cpu(g, inputs, uniforms, job.textures, run);
    return run;
}

bool uses_derivatives(const Graph& g) {
    for (uint32_t id : g.live_nodes())
        if (g.node(id).op == Op::Ddx || g.node(id).op == Op::Ddy) return true;
    return false;
}

const std::map<std::string, TextureData>& probe_scene_textures() {
    // Only the scene's own images depend on the size; the node textures (height map, normal
    // map, sky cube, ...) are made at their fixed sizes.
    static const std::map<std::string, TextureData> textures =
        make_synthetic_scene(64, 64).textures;
    return textures;
}

std::optional<ProbeInputs> prepare_probe(const CatalogNode& node, const std::string& csv_path,
                                         const std::vector<std::string>& param_specs,
                                         bool allow_out_of_range, std::string& error) {
    ProbeInputs in{probe_graph(node), {}, {}, {}};
    in.layout = probe_layout(in.graph);
    auto tuples = read_probe_csv(csv_path, probe_columns(in.layout.inputs), error);
    if (!tuples) return std::nullopt;
    auto params = parse_probe_parameters(param_specs, error);
    if (!params) return std::nullopt;
    in.tuples = std::move(*tuples);
    in.params = std::move(*params);
    if (const size_t rows = in.tuples.size() / in.layout.input_stride;
        uses_derivatives(in.graph) && rows % 4 != 0) {
        error = fmt::format("{}: {} takes ddx / ddy over 2x2 quads of data rows 4k..4k+3; {} rows "
                            "are not whole quads",
                            csv_path, node.name, rows);
        return std::nullopt;
    }
    if (auto e = check_probe_parameters(in.graph, in.params, allow_out_of_range)) {
        error = *e;
        return std::nullopt;
    }
    return in;
}

} // namespace watergen
