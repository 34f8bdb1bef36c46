// watergen probe: one node over a CSV of input tuples, on the GPU and on the CPU.
#include <cstdio>

#include <fmt/format.h>

#include "commands.h"
#include "watergen/eval/probe/probe_output.h"
#include "watergen/water/node_catalog.h"

namespace watergen::cli {

namespace {

void print_summary(const ProbeSummary& s) {
    auto side = [](const ProbeSideCount& c) {
        return fmt::format("{} ({} NaN, {} Inf)", c.non_finite(), c.nan, c.inf);
    };
    std::printf("  non-finite results: gpu %zu, cpu double %zu, cpu float %zu, cpu half %zu\n",
                s.gpu.non_finite(), s.cpu_double.non_finite(), s.cpu_float.non_finite(),
                s.cpu_half.non_finite());
    if (s.gpu.non_finite() + s.cpu_double.non_finite() + s.cpu_float.non_finite() +
            s.cpu_half.non_finite() >
        0)
        std::printf("    gpu %s, cpu double %s, cpu float %s, cpu half %s\n", side(s.gpu).c_str(),
                    side(s.cpu_double).c_str(), side(s.cpu_float).c_str(),
                    side(s.cpu_half).c_str());
    std::printf("  max |gpu - cpu float| %.3g, max |gpu - cpu double| %.3g, max |cpu half - cpu "
                "double| %.3g "
                "(over values finite on both sides)\n",
                s.max_gpu_vs_cpu_float, s.max_gpu_vs_cpu_double, s.max_half_vs_double);
    if (s.gpu_vs_cpu_half.values > 0) {
        const HalfAgreement& a = s.gpu_vs_cpu_half;
        const double n = static_cast<double>(a.values);
        std::printf("  strict half, gpu vs cpu half: %.2f%% of values equal, %.2f%% within 1 ulp, "
                    "max %lld ulps, max |gpu - cpu half| %.3g\n",
                    100.0 * a.equal / n, 100.0 * a.within_1 / n, static_cast<long long>(a.max_ulps),
                    s.max_gpu_vs_cpu_half);
    }
}

struct ProbeOptions {
    std::string node, in, out, language = "glsl";
    std::vector<std::string> params;
    bool allow_out_of_range = false, strict_half = false;
    RunnerSetup runner;
};

int run_probe_command(const ProbeOptions& o, const Common& common) {
    std::string error;
    const auto probe =
        prepare_probe(*find_catalog_node(o.node), o.in, o.params, o.allow_out_of_range, error);
    if (!probe) return stop(error, RunStatus::BadInput);
    std::string cache;
    auto runner = create_runner(o.runner, &cache);
    if (!runner) return kNoDevice;
    if (o.strict_half && !has_float16(*runner, "; --strict-half needs it")) return kNoDevice;
    const ProbeOutput out =
        write_probe(*runner, *probe, o.language == "hlsl" ? Language::Hlsl : Language::Glsl,
                    o.strict_half, o.out);
    if (out.status != RunStatus::Ok)
        return stop(out.run.diagnostics, out.error, out.status, common);
    print_diagnostics(out.run.diagnostics, common);
    std::printf("%s (%s path%s) on %s: %zu tuples, dispatch %.2f ms (pipeline %.2f ms, Mesa "
                "shader cache %s)\n",
                o.node.c_str(), o.language.c_str(), o.strict_half ? ", strict half" : "",
                runner->device_info().name.c_str(), out.run.tuples, out.run.dispatch_ms,
                out.run.pipeline_ms, cache.c_str());
    for (const auto& t : probe->graph.textures()) {
        const TextureData& data = probe_scene_textures().at(t.name);
        std::printf("  texture %s: %ux%u%s from the synthetic scene, linear, clamp to edge\n",
                    t.name.c_str(), data.width, data.height, data.layers == 6 ? " x 6 faces" : "");
    }
    const ProbeSummary& summary = out.summary;
    print_summary(summary);
    std::printf("  wrote %s\n", o.out.c_str());
    if (!summary.gpu_stable()) {
        std::fprintf(stderr,
                     "watergen: error: %s: %zu tuple%s non-finite on the GPU where the CPU %s "
                     "result is finite (first: data row %zu)\n",
                     o.node.c_str(), summary.gpu_only_non_finite,
                     summary.gpu_only_non_finite == 1 ? " is" : "s are",
                     o.strict_half ? "half" : "float", summary.first_gpu_only_tuple + 1);
        return kFailed;
    }
    return kOk;
}

} // namespace

Runner add_probe_command(CLI::App& app, const Common& common) {
    auto o = std::make_shared<ProbeOptions>();
    std::vector<std::string> names;
    for (const auto& n : node_catalog())
        names.push_back(n.name);
    app.add_option("--node", o->node, "node to probe: " + catalog_names())
        ->required()
        ->check(CLI::IsMember(names));
    app.add_option(
           "--in", o->in,
           "CSV of input tuples; header = the node's input columns (vectors as name.x,name.y,...)")
        ->required();
    app.add_option("--out", o->out,
                   "CSV to write: the inputs, then per output component gpu, cpu_double, "
                   "cpu_float, cpu_half")
        ->required();
    app.add_option("--language", o->language,
                   "language path of the compute shader: glsl or hlsl (default glsl)")
        ->check(CLI::IsMember({"glsl", "hlsl"}));
    app.add_option("--param", o->params,
                   "override a parameter on GPU and CPU: name=value[,value...] (repeatable; "
                   "checked against the "
                   "parameter's declared range)");
    app.add_flag("--allow-out-of-range", o->allow_out_of_range,
                 "pass --param values outside the declared range (or non-finite) to GPU and CPU "
                 "unchecked, for "
                 "stress tests");
    app.add_flag("--strict-half", o->strict_half,
                 "run the node in 16-bit arithmetic on the GPU (GLSL float16_t, HLSL half) and "
                 "compare with the CPU half evaluator, in binary16 ulps");
    add_runner_options(app, o->runner);
    return [o, &common]() { return run_probe_command(*o, common); };
}

} // namespace watergen::cli
