// Compile benchmark: the in-process chain against the same chain run through the
// command-line tools as processes, measured in the same run on the same shaders.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "watergen/plan/covering_array.h"
#include "watergen/pipeline/output_writer.h"
#include "watergen/toolchain/tool_process_chain.h"
#include "watergen/pipeline/variant_build.h"

namespace watergen::cli {

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

template <class F> double time_ms(F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

struct Row {
    std::string key;
    double in_process_ms = 0, processes_ms = 0;
};

} // namespace

Runner add_bench_compile_command(CLI::App& app, const Common& common) {
    struct Options {
        int repeat = 5;
        std::string out = "out/bench";
    };
    auto o = std::make_shared<Options>();
    app.add_option("--repeat", o->repeat, "timed repetitions per variant and chain; the median is reported (default 5)")
        ->check(CLI::Range(1, 100));
    app.add_option("--out", o->out, "directory for compile.csv and compile.json (default out/bench)");
    return [o, &common]() {
        glslang_warm_up();
        const std::filesystem::path work = std::filesystem::temp_directory_path() / "watergen-bench-compile";
        std::filesystem::create_directories(work);
        std::vector<Row> rows;
        for (const Variant& v : pairwise_covering_variants()) {
            std::vector<CompileRequest> requests;
            Diagnostics ds;
            const WaterShader shader = build_water_shader(v);
            for (Language lang : {Language::Glsl, Language::Hlsl}) {
                const auto src = lang == Language::Glsl ? SourceLanguage::Glsl : SourceLanguage::Hlsl;
                const EmittedShader frag = emit_fragment(shader.fragment, lang, "water.frag", v.key(), ds);
                const EmittedShader vert = emit_fullscreen_vertex(lang, "water.vert", v.key());
                requests.push_back({src, ShaderStage::Fragment, frag.source, "water.frag", "main"});
                requests.push_back({src, ShaderStage::Vertex, vert.source, "water.vert", "main"});
            }
            if (has_errors(ds)) {
                print_diagnostics(ds, common);
                return kFailed;
            }
            Row row{v.key()};
            std::vector<double> inproc, procs;
            for (int r = 0; r < o->repeat; ++r) {
                bool ok = true;
                inproc.push_back(time_ms([&] {
                    for (const auto& req : requests) ok = run_toolchain(req).ok() && ok;
                }));
                std::string error;
                procs.push_back(time_ms([&] {
                    for (const auto& req : requests) {
                        const auto res = run_tool_process_chain(req, work.string());
                        if (!res.ok) error = res.error;
                    }
                }));
                if (!ok || !error.empty()) {
                    std::fprintf(stderr, "watergen: error: %s: %s\n", v.key().c_str(),
                                 error.empty() ? "in-process chain failed" : error.c_str());
                    return kFailed;
                }
            }
            row.in_process_ms = median(inproc);
            row.processes_ms = median(procs);
            rows.push_back(row);
        }
        std::filesystem::remove_all(work);

        std::printf("%-46s %14s %14s %8s\n", "variant (4 shaders: GLSL+HLSL, vert+frag)", "in-process ms", "processes ms", "ratio");
        std::string csv = "variant,in_process_ms,processes_ms,ratio\n";
        nlohmann::ordered_json json = nlohmann::ordered_json::array();
        std::vector<double> ratios, in_all, proc_all;
        for (const auto& r : rows) {
            const double ratio = r.processes_ms / r.in_process_ms;
            ratios.push_back(ratio);
            in_all.push_back(r.in_process_ms);
            proc_all.push_back(r.processes_ms);
            std::printf("%-46s %14.2f %14.2f %7.1fx\n", r.key.c_str(), r.in_process_ms, r.processes_ms, ratio);
            csv += fmt::format("\"{}\",{:.3f},{:.3f},{:.2f}\n", r.key, r.in_process_ms, r.processes_ms, ratio);
            json.push_back({{"variant", r.key}, {"in_process_ms", r.in_process_ms}, {"processes_ms", r.processes_ms}, {"ratio", ratio}});
        }
        std::printf("%-46s %14.2f %14.2f %7.1fx\n", "median over variants", median(in_all), median(proc_all), median(ratios));
        std::printf("chain: glslang -> spirv-val -> spirv-opt -O -> spirv-val -> SPIRV-Cross (GLSL 330, ESSL 300, MSL) + round trip + reflection; median of %d runs\n", o->repeat);
        std::filesystem::create_directories(o->out);
        const auto dir = std::filesystem::path(o->out);
        nlohmann::ordered_json doc = {{"repeat", o->repeat}, {"median_ratio", median(ratios)}, {"variants", json}};
        for (auto [name, text] : {std::pair{"compile.csv", csv}, std::pair{"compile.json", doc.dump(2) + "\n"}})
            if (auto e = write_file_atomically(dir / name, text)) {
                std::fprintf(stderr, "watergen: error: %s\n", e->c_str());
                return kFailed;
            }
        std::printf("wrote %s and %s\n", (dir / "compile.csv").string().c_str(), (dir / "compile.json").string().c_str());
        return kOk;
    };
}

} // namespace watergen::cli
