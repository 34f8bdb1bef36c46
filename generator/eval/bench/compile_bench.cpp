#include "watergen/eval/bench/compile_bench.h"
#include "watergen/eval/measure/interleaved_timing.h"

#include <algorithm>
#include <chrono>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "watergen/ir/emit/emitter.h"
#include "watergen/pipeline/output/output_writer.h"
#include "watergen/plan/covering_array.h"
#include "watergen/toolchain/tool_process_chain.h"
#include "watergen/toolchain/toolchain.h"
#include "watergen/water/water_shader.h"

namespace watergen {

namespace {

template <class F> double time_ms(F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// GLSL and HLSL, fragment and vertex.
std::vector<CompileRequest> compile_requests(const Variant& v, Diagnostics& ds) {
    std::vector<CompileRequest> requests;
    const WaterShader shader = build_water_shader(v);
    for (Language lang : {Language::Glsl, Language::Hlsl}) {
        const auto src = lang == Language::Glsl ? SourceLanguage::Glsl : SourceLanguage::Hlsl;
        const EmittedShader frag = emit_fragment(shader.fragment, lang, "water.frag", v.key(), ds);
        const EmittedShader vert = emit_fullscreen_vertex(lang, "water.vert", v.key());
        requests.push_back({src, ShaderStage::Fragment, frag.source, "water.frag", "main"});
        requests.push_back({src, ShaderStage::Vertex, vert.source, "water.vert", "main"});
    }
    return requests;
}

// Times both chains on one variant's shaders; "" or what failed.
std::string time_chains(const std::vector<CompileRequest>& requests, int repeat,
                        const std::filesystem::path& work, CompileBenchRow& row) {
    std::vector<double> in_process, processes;
    for (int r = 0; r < repeat; ++r) {
        bool ok = true;
        in_process.push_back(time_ms([&] {
            for (const auto& req : requests)
                ok = run_toolchain(req).ok() && ok;
        }));
        std::string error;
        processes.push_back(time_ms([&] {
            for (const auto& req : requests) {
                const auto res = run_tool_process_chain(req, work.string());
                if (!res.ok) error = res.error;
            }
        }));
        if (!ok || !error.empty()) return error.empty() ? "in-process chain failed" : error;
    }
    row.in_process_ms = median(in_process);
    row.processes_ms = median(processes);
    return "";
}

} // namespace

CompileBench run_compile_bench(int repeat) {
    glslang_warm_up();
    CompileBench bench;
    const std::filesystem::path work = make_unique_directory(
        std::filesystem::temp_directory_path(), "watergen-bench-compile-", &bench.error);
    if (work.empty()) return bench;
    for (const Variant& v : pairwise_covering_variants()) {
        Diagnostics ds;
        const std::vector<CompileRequest> requests = compile_requests(v, ds);
        if (has_errors(ds)) {
            bench.diagnostics = std::move(ds);
            break;
        }
        CompileBenchRow row{v.key()};
        if (const std::string error = time_chains(requests, repeat, work, row); !error.empty()) {
            bench.error = v.key() + ": " + error;
            break;
        }
        bench.rows.push_back(row);
    }
    std::error_code ignored;
    std::filesystem::remove_all(work, ignored);
    std::vector<double> in_process, processes, ratios;
    for (const auto& r : bench.rows) {
        in_process.push_back(r.in_process_ms);
        processes.push_back(r.processes_ms);
        ratios.push_back(r.ratio());
    }
    bench.median_in_process_ms = median(in_process);
    bench.median_processes_ms = median(processes);
    bench.median_ratio = median(ratios);
    bench.csv = "variant,in_process_ms,processes_ms,ratio\n";
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const auto& r : bench.rows) {
        bench.csv += fmt::format("\"{}\",{:.3f},{:.3f},{:.2f}\n", r.key, r.in_process_ms,
                                 r.processes_ms, r.ratio());
        rows.push_back({{"variant", r.key},
                        {"in_process_ms", r.in_process_ms},
                        {"processes_ms", r.processes_ms},
                        {"ratio", r.ratio()}});
    }
    const nlohmann::ordered_json doc = {
        {"repeat", repeat}, {"median_ratio", bench.median_ratio}, {"variants", rows}};
    bench.json = doc.dump(2) + "\n";
    return bench;
}

} // namespace watergen
