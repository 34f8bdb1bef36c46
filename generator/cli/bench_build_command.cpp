// Build benchmark: variants per second of `watergen build`, cold (empty cache) and warm (a
// no-op rebuild from a full cache), on one thread and on all, for the full space and for a
// pruned example (a material and its scenes).
//
// The full space's variants are far too many to compile in a benchmark, so for it the
// bench measures (1) enumerating it and checking its rules, (2) planning each given scene over
// it (which variants the scene reaches), both over all of it, and (3) building an evenly
// spaced sample of it (--sample, every k-th variant in enumeration order) through the same
// jobs as `watergen build` (compose, emit, hash, cache or toolchain), without writing files.
// The pruned example is a complete `watergen build`, output written.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <unistd.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "watergen/pipeline/build_output.h"
#include "watergen/toolchain/glslang_stage.h"
#include "watergen/pipeline/output_writer.h"

namespace watergen::cli {

namespace {

namespace fs = std::filesystem;

template <class F> double seconds_of(F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Material full_material() {
    MaterialBuilder b("full");
    for (const auto& a : axes()) b.offer_all(a.name);
    Diagnostics ds;
    return *b.build(ds);
}

struct Row {
    std::string what;
    size_t variants = 0;
    double seconds = 0;
    std::string note;
};

} // namespace

Runner add_bench_build_command(CLI::App& app, const Common& common) {
    struct Options {
        std::string material;
        std::vector<std::string> scenes;
        std::string out = "out/bench";
        unsigned threads = 0;
        size_t sample = 48;
    };
    auto o = std::make_shared<Options>();
    app.add_option("material", o->material, "material of the pruned example (default: the built-in default material)");
    app.add_option("--scene", o->scenes, "scenes of the pruned example (repeatable)");
    app.add_option("--jobs,-j", o->threads, "threads of the 'all threads' runs (default: every hardware thread)");
    app.add_option("--sample", o->sample,
                   "full-space variants to build, evenly spaced (default 48)")
        ->check(CLI::Validator(
            [](std::string& in) { return CLI::Range(size_t{1}, count_variants(full_space()))(in); },
            "INT in [1 - the full space's size]"));
    app.add_option("--out", o->out, "directory for build.csv and build.json (default out/bench)");
    return [o, &common]() {
        Material example;
        std::vector<SceneFacts> scenes;
        if (!load_material_and_scenes(o->material, o->scenes, example, scenes, common)) return kUsage;
        const unsigned all = o->threads ? o->threads : hardware_threads();
        const fs::path work = fs::temp_directory_path() / fmt::format("watergen-bench-build-{}", ::getpid());
        fs::remove_all(work);
        std::vector<Row> rows;

        const Material full = full_material();
        size_t n = 0;
        rows.push_back({"full space: enumerate + check rules", 0, seconds_of([&] { n = count_variants(full.space); }), ""});
        rows.back().variants = n;
        for (const auto& s : scenes) {
            Diagnostics ds;
            size_t reached = 0;
            const double t = seconds_of([&] {
                if (auto p = plan_scene(full, s, ds)) reached = p->variants.size();
            });
            rows.push_back({"full space: plan scene " + s.name, n, t, fmt::format("reaches {}", reached)});
        }

        glslang_warm_up();
        // One throwaway build so every glslang front end (GLSL 450, HLSL, 330, 300 es) has
        // built its tables before anything is timed.
        {
            BuildRequest warm{default_material(), {}, work / "warm-up", {}};
            warm.options.threads = 1;
            build_material(warm);
        }
        // The full space: a sample built as jobs (nothing written).
        std::vector<BuildJob> sample;
        {
            const size_t step = std::max<size_t>(1, n / o->sample);
            size_t i = 0;
            enumerate(full.space, [&](const Variant& v) {
                if (i++ % step == 0 && sample.size() < o->sample) sample.push_back({"sample", v, nullptr, all_targets()});
            });
        }
        for (unsigned threads : {1u, all}) {
            const BuildCache cache(work / fmt::format("cache-sample-{}", threads));
            for (const char* temperature : {"cold", "warm"}) {
                BuildOptions options;
                options.threads = threads;
                options.cache = cache;
                std::vector<JobResult> results;
                const double t = seconds_of([&] { results = run_build_jobs(full, sample, options); });
                size_t failed = 0, cached = 0;
                for (const auto& r : results) {
                    failed += !r.ok();
                    cached += r.cached;
                }
                rows.push_back({fmt::format("full space, sample of {} (every {}-th): build {}, {} thread{}", sample.size(),
                                            std::max<size_t>(1, n / o->sample), temperature, threads, threads == 1 ? "" : "s"),
                                sample.size(), t, fmt::format("{} cached, {} failed", cached, failed)});
            }
        }
        // The pruned example: complete builds, output written.
        const std::string label = "pruned example (" + example.name +
                                  (scenes.empty() ? ", unpruned" : ", " + std::to_string(scenes.size()) + " scenes") + ")";
        for (unsigned threads : {1u, all}) {
            const fs::path cache = work / fmt::format("cache-example-{}", threads);
            const fs::path out = work / fmt::format("out-example-{}", threads);
            for (const char* temperature : {"cold", "warm"}) {
                BuildRequest r{example, scenes, out, {}};
                r.options.threads = threads;
                r.options.cache = BuildCache(cache);
                const BuildSummary s = build_material(r);
                if (!s.ok()) {
                    print_diagnostics(s.diagnostics, common);
                    fs::remove_all(work);
                    return kFailed;
                }
                rows.push_back({fmt::format("{}: build {}, {} thread{}", label, temperature, threads, threads == 1 ? "" : "s"),
                                s.variants, s.seconds,
                                fmt::format("{} built, {} cached, {} shared, {} same shader", s.built, s.cached, s.shared, s.same)});
            }
        }
        fs::remove_all(work);

        std::printf("%-78s %9s %9s %12s  %s\n", "what", "variants", "seconds", "variants/s", "");
        std::string csv = "what,variants,seconds,variants_per_second,note\n";
        nlohmann::ordered_json json = nlohmann::ordered_json::array();
        for (const auto& r : rows) {
            const double rate = r.seconds > 0 ? r.variants / r.seconds : 0.0;
            std::printf("%-78s %9zu %9.3f %12.1f  %s\n", r.what.c_str(), r.variants, r.seconds, rate, r.note.c_str());
            csv += fmt::format("\"{}\",{},{:.4f},{:.1f},\"{}\"\n", r.what, r.variants, r.seconds, rate, r.note);
            json.push_back({{"what", r.what}, {"variants", r.variants}, {"seconds", r.seconds}, {"variants_per_second", rate}, {"note", r.note}});
        }
        std::printf("cold: empty cache, every distinct shader through glslang (GLSL + HLSL), spirv-val, spirv-opt, SPIRV-Cross "
                    "and reflection; warm: the same build again (no-op: every variant from the cache); %u hardware threads\n",
                    hardware_threads());
        fs::create_directories(o->out);
        const fs::path dir = o->out;
        for (auto [name, text] : {std::pair{"build.csv", csv}, std::pair{"build.json", json.dump(2) + "\n"}})
            if (auto e = write_file_atomically(dir / name, text)) {
                std::fprintf(stderr, "watergen: error: %s\n", e->c_str());
                return kFailed;
            }
        std::printf("wrote %s and %s\n", (dir / "build.csv").string().c_str(), (dir / "build.json").string().c_str());
        return kOk;
    };
}

} // namespace watergen::cli
