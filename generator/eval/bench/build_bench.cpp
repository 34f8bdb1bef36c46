#include "watergen/eval/bench/build_bench.h"
#include "watergen/pipeline/output/output_writer.h"

#include <algorithm>
#include <chrono>
#include <unistd.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "watergen/pipeline/build/build_output.h"
#include "watergen/toolchain/glslang_stage.h"

namespace watergen {

namespace {

namespace fs = std::filesystem;

template <class F> double seconds_of(F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Material full_material() {
    MaterialBuilder b("full");
    for (const auto& a : axes())
        b.offer_all(a.name);
    Diagnostics ds;
    return *b.build(ds);
}

// Enumerating the full space and planning each scene over it; returns the space's size.
size_t measure_planning(const Material& full, const std::vector<SceneFacts>& scenes,
                        std::vector<BuildBenchRow>& rows) {
    size_t n = 0;
    rows.push_back({"full space: enumerate + check rules", 0,
                    seconds_of([&] { n = count_variants(full.space); }), ""});
    rows.back().variants = n;
    for (const auto& s : scenes) {
        Diagnostics ds;
        size_t reached = 0;
        const double t = seconds_of([&] {
            if (auto p = plan_scene(full, s, ds)) reached = p->variants.size();
        });
        rows.push_back(
            {"full space: plan scene " + s.name, n, t, fmt::format("reaches {}", reached)});
    }
    return n;
}

// An evenly spaced sample of the full space built as jobs (nothing written), cold and warm.
void measure_sample(const Material& full, size_t n, size_t wanted, unsigned all,
                    const fs::path& work, std::vector<BuildBenchRow>& rows) {
    std::vector<BuildJob> sample;
    const size_t step = std::max<size_t>(1, n / wanted);
    size_t i = 0;
    enumerate(full.space, [&](const Variant& v) {
        if (i++ % step == 0 && sample.size() < wanted)
            sample.push_back({"sample", v, nullptr, all_targets()});
    });
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
            rows.push_back(
                {fmt::format("full space, sample of {} (every {}-th): build {}, {} thread{}",
                             sample.size(), step, temperature, threads, threads == 1 ? "" : "s"),
                 sample.size(), t, fmt::format("{} cached, {} failed", cached, failed)});
        }
    }
}

// The pruned example: complete builds, output written. False (diagnostics set) when one fails.
bool measure_example(const BuildBenchRequest& r, unsigned all, const fs::path& work,
                     BuildBenchResult& out) {
    const std::string label =
        "pruned example (" + r.example.name +
        (r.scenes.empty() ? ", unpruned" : ", " + std::to_string(r.scenes.size()) + " scenes") +
        ")";
    for (unsigned threads : {1u, all}) {
        const fs::path cache = work / fmt::format("cache-example-{}", threads);
        const fs::path dir = work / fmt::format("out-example-{}", threads);
        for (const std::string temperature : {"cold", "warm", "no-op"}) {
            BuildRequest build{r.example, r.scenes, dir, {}};
            build.options.threads = threads;
            build.options.cache = BuildCache(cache);
            // The warm build stores its record, so the next one finds nothing to do.
            if (temperature != "cold") build.inputs_hash = "bench example";
            BuildSummary s = build_material(build);
            if (!s.ok()) {
                out.diagnostics = std::move(s.diagnostics);
                return false;
            }
            out.rows.push_back({fmt::format("{}: build {}, {} thread{}", label, temperature,
                                            threads, threads == 1 ? "" : "s"),
                                s.variants, s.seconds,
                                s.up_to_date
                                    ? fmt::format("up to date: {} files verified", s.files)
                                    : fmt::format("{} built, {} cached, {} shared, {} same shader",
                                                  s.built, s.cached, s.shared, s.same)});
        }
    }
    return true;
}

} // namespace

BuildBenchResult bench_build(const BuildBenchRequest& request) {
    BuildBenchResult out;
    const unsigned all = request.threads ? request.threads : hardware_threads();
    // A directory of its own (never another run's, whatever its PID), or the one asked for.
    std::string why;
    const fs::path work =
        request.work.empty()
            ? make_unique_directory(fs::temp_directory_path(), "watergen-bench-build-", &why)
            : request.work;
    if (work.empty()) {
        out.diagnostics.push_back({Severity::Error, "", 0, 0, "", why});
        return out;
    }
    if (!request.work.empty()) fs::remove_all(work);
    const Material full = full_material();
    const size_t n = measure_planning(full, request.scenes, out.rows);

    glslang_warm_up();
    // One throwaway build so every glslang front end (GLSL 450, HLSL, 330, 300 es) has
    // built its tables before anything is timed.
    {
        BuildRequest warm{default_material(), {}, work / "warm-up", {}};
        warm.options.threads = 1;
        build_material(warm);
    }
    measure_sample(full, n, request.sample, all, work, out.rows);
    measure_example(request, all, work, out);
    fs::remove_all(work);
    out.csv = "what,variants,seconds,variants_per_second,note\n";
    nlohmann::ordered_json json = nlohmann::ordered_json::array();
    for (const auto& r : out.rows) {
        out.csv += fmt::format("\"{}\",{},{:.4f},{:.1f},\"{}\"\n", r.what, r.variants, r.seconds,
                               r.rate(), r.note);
        json.push_back({{"what", r.what},
                        {"variants", r.variants},
                        {"seconds", r.seconds},
                        {"variants_per_second", r.rate()},
                        {"note", r.note}});
    }
    out.json = json.dump(2) + "\n";
    return out;
}

} // namespace watergen
