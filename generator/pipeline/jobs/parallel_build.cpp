#include "watergen/pipeline/jobs/parallel_build.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include <fmt/format.h>
#include <xxhash.h>

#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/plan/shader_fold.h"
#include "watergen/toolchain/glslang_stage.h"

namespace watergen {

namespace {

// Kinds of file a target keeps, by suffix after "water.<stage>".
bool wanted(const std::string& path, const std::vector<Target>& targets) {
    auto has = [&](Target t) {
        return std::find(targets.begin(), targets.end(), t) != targets.end();
    };
    if (path == "variant.json" || path == "pass.json") return true;
    const bool glsl_dir = path.rfind("glsl/", 0) == 0, hlsl_dir = path.rfind("hlsl/", 0) == 0;
    auto ends = [&](const char* s) {
        const std::string suffix = s;
        return path.size() > suffix.size() &&
               path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
    };
    // The HLSL path's SPIR-V and reflection come with the HLSL target; cross-compiled text
    // comes from the GLSL path only (the HLSL path's would be the same program again).
    if (hlsl_dir) {
        if (!has(Target::Hlsl)) return false;
        if (ends(".hlsl")) return true;
        if (ends(".spv")) return has(Target::Spirv);
        if (ends(".reflect.json")) return has(Target::Reflection);
        return false;
    }
    if (!glsl_dir) return false;
    if (ends(".330.glsl")) return has(Target::Glsl330);
    if (ends(".300es.glsl")) return has(Target::Essl300);
    if (ends(".metal")) return has(Target::Msl);
    if (ends(".spv")) return has(Target::Spirv);
    if (ends(".reflect.json")) return has(Target::Reflection);
    if (ends(".glsl")) return has(Target::Glsl);
    return false;
}

// The stages a build compiles for a job, keyed by content (StageMemo): each language's in
// pipeline order (vertex, [tessellation control, evaluation,] fragment), GLSL first.
using StageKeys = std::vector<StageKey>;

// What phase 1 learns of a shader from its sources, emitted once per language.
struct ShaderHashes {
    std::string content, shape;
    StageKeys stages;
};

// What the files of a variant depend on besides the toolchain: its sources (which carry the
// key in their stamp), the slots of its resources and the metadata of the parameters they read,
// which variant.json reports. The shape is the same without the key: the sources with their
// stamps blank.
ShaderHashes hash_shader(const WaterShader& shader, const std::string& stamp_key,
                         const EmitOptions& emit, const StageCompile& compile, Diagnostics& ds) {
    std::vector<std::string> parts{shader.key(), shader.preset}, shape{shader.preset};
    ShaderHashes h;
    const std::array<LanguageBuild, 2> languages = emit_shader_stages(shader, emit, ds);
    if (has_errors(ds)) return h;
    for (const LanguageBuild& built : languages) {
        const Language lang = built.language;
        // The fragment's source first: the order the hashes of screen-pass builds have always
        // had, so their cache entries stay valid.
        std::vector<const StageBuild*> stages = built.stages();
        std::rotate(stages.begin(), stages.end() - 1, stages.end());
        for (const StageBuild* stage : stages) {
            const EmittedShader& e = stage->source;
            parts.push_back(e.source);
            shape.push_back(blank_stamp(e.source, stamp_key));
            h.stages.push_back(stage_key(stage_request(e), stage_cross(lang, compile), stamp_key));
        }
        if (lang != Language::Glsl) continue;
        const EmittedShader& frag = built.fragment.source;
        parts.push_back(slots_text(frag.interface));
        shape.push_back(parts.back());
        for (const Parameter& p : frag.interface.parameters) {
            std::string s = fmt::format("{}|{}|{}|{}|{}|{}|{}", p.name, static_cast<int>(p.type),
                                        p.min, p.max, p.unit, p.seed, p.origin);
            for (double v : p.default_value)
                s += fmt::format("|{}", v);
            parts.push_back(s);
            shape.push_back(s);
        }
    }
    h.content = content_hash(parts);
    h.shape = content_hash(shape); // equal shaders under different keys are still equal
    return h;
}

// The job's shader: composed from the material and folded under its scene's facts (what
// folding did into `report`, if given).
WaterShader compose_job(const Material& material, const BuildJob& job, Diagnostics& ds,
                        FoldReport* report = nullptr) {
    WaterShader shader = job.shader ? material.compose(*job.shader) : material.compose(job.variant);
    const Diagnostics& graph_errors = shader.fragment.diagnostics();
    ds.insert(ds.end(), graph_errors.begin(), graph_errors.end());
    if (has_errors(ds) || !job.facts) return shader;
    FoldReport folded = fold_water_shader(shader, *job.facts);
    if (report) *report = std::move(folded);
    return shader;
}

// Phase 1 for one job: compose, fold, hash (no compiler involved). The shader is not kept:
// phase 2 composes it again (a few ms) rather than hold every job's graph at once.
void compose_and_hash(const Material& material, const BuildJob& job, const EmitOptions& emit,
                      const StageCompile& compile, JobResult& r, StageKeys& stages) {
    const WaterShader shader = compose_job(material, job, r.diagnostics, &r.fold);
    if (has_errors(r.diagnostics)) return;
    r.folded = job.facts != nullptr;
    ShaderHashes h = hash_shader(shader, job_key(job), emit, compile, r.diagnostics);
    if (has_errors(r.diagnostics)) return;
    r.content_hash = std::move(h.content);
    r.shape_hash = std::move(h.shape);
    stages = std::move(h.stages);
}

struct BuildPlan {
    std::vector<size_t> to_build;
    std::vector<std::pair<size_t, size_t>> copies;   // (job, job of the batch it takes files of)
    std::vector<std::pair<size_t, size_t>> borrowed; // (job, job of an earlier batch)
};

BuildLedger::Hash128 hash_of(const std::string& text) {
    return BuildLedger::hash_of(text);
}

bool has_targets(const std::vector<Target>& all, const std::vector<Target>& some) {
    return std::all_of(some.begin(), some.end(),
                       [&](Target t) { return std::find(all.begin(), all.end(), t) != all.end(); });
}

// Variants of one scene that folded to the same shader: build the first only. Equal
// content in different scenes (the same variant folded alike) is built once and shared: taken
// from the builder when it is of this batch, read back when of an earlier one (if it kept every
// target this job needs; else built again).
BuildPlan plan_builds(const JobList& all, size_t begin, const std::vector<BuildJob>& batch,
                      std::vector<JobResult>& results, BuildLedger& ledger, bool can_read_back) {
    BuildPlan plan;
    // A job of this batch, or (made again from the list) of an earlier one.
    auto job = [&](size_t i) { return i >= begin ? batch[i - begin] : all.at(i); };
    const std::string last_scene = all.empty() ? "" : all.at(all.size() - 1).scene;
    for (size_t i = begin; i < begin + batch.size(); ++i) {
        JobResult& r = results[i - begin];
        const BuildJob& own = batch[i - begin];
        if (!r.ok()) continue;
        if (own.scene != ledger.scene) {
            ledger.first.clear(); // a shape is the same shader only within a scene
            ledger.scene = own.scene;
        }
        auto [it, inserted] =
            ledger.first.try_emplace(hash_of(r.shape_hash), BuildLedger::Built{i, nullptr});
        if (!inserted) {
            r.same_as = job_key(job(it->second.job));
            r.same_as_job = it->second.job;
            if (it->second.job < begin) r.names = it->second.names; // of an earlier batch
            continue;
        }
        // Only a later scene can take this job's files: the last scene's are not kept.
        const bool later_scenes = own.scene != last_scene;
        const BuildLedger::Hash128 content = hash_of(r.content_hash);
        const auto b = ledger.built.find(content);
        if (b == ledger.built.end()) {
            plan.to_build.push_back(i);
            if (later_scenes) ledger.built.emplace(content, BuildLedger::Built{i, nullptr});
        } else if (b->second.job >= begin) {
            plan.copies.emplace_back(i, b->second.job);
        } else if (can_read_back && b->second.names &&
                   has_targets(job(b->second.job).targets, own.targets)) {
            plan.borrowed.emplace_back(i, b->second.job);
        } else {
            plan.to_build.push_back(i);
        }
    }
    return plan;
}

// Phase 2 for one job: its files from the cache or the toolchain (all targets), if it built.
// The shader is composed only when the cache does not have the files.
std::optional<FileMap> load_or_build(const BuildOptions& options, const EmitOptions& emit,
                                     const std::function<WaterShader()>& compose,
                                     const StageCompile& compile, JobResult& r,
                                     const std::vector<std::string>& expected_files) {
    CacheUse use =
        options.cache.load_or_make(r.content_hash, expected_files, [&]() -> std::optional<FileMap> {
            const VariantBuild build = build_shader(compose(), emit, compile);
            r.diagnostics.insert(r.diagnostics.end(), build.diagnostics.begin(),
                                 build.diagnostics.end());
            if (!build.ok()) return std::nullopt;
            return variant_files(build);
        });
    r.cached = use.cached;
    r.cache_rejected = std::move(use.rejected);
    return std::move(use.files);
}

} // namespace

// Each distinct list of file names once, shared by the jobs that write it.
class NameLists {
  public:
    std::shared_ptr<const std::vector<std::string>> intern(std::vector<std::string> names) {
        std::lock_guard<std::mutex> guard(lock_);
        const auto [it, fresh] = lists_.try_emplace(std::move(names));
        if (fresh) it->second = std::make_shared<const std::vector<std::string>>(it->first);
        return it->second;
    }

  private:
    std::mutex lock_;
    std::map<std::vector<std::string>, std::shared_ptr<const std::vector<std::string>>> lists_;
};

const std::vector<std::string>& JobResult::file_names() const {
    static const std::vector<std::string> none;
    return names ? *names : none;
}

unsigned hardware_threads() {
    return std::max(1u, std::thread::hardware_concurrency());
}

unsigned max_jobs() {
    return kJobsPerHardwareThread * hardware_threads();
}

void parallel_for(size_t n, unsigned threads, const std::function<void(size_t)>& task) {
    // Never more threads than tasks, nor past max_jobs(): each thread costs a stack and its own
    // glslang state, and past a few per core they only contend.
    const unsigned asked = threads == 0 ? hardware_threads() : std::min(threads, max_jobs());
    const unsigned workers = static_cast<unsigned>(std::min<size_t>(asked, std::max<size_t>(n, 1)));
    if (workers <= 1) {
        for (size_t i = 0; i < n; ++i)
            task(i);
        return;
    }
    std::atomic<size_t> next{0};
    std::vector<std::thread> pool;
    for (unsigned w = 0; w < workers; ++w)
        pool.emplace_back([&] {
            for (size_t i; (i = next++) < n;)
                task(i);
        });
    for (auto& t : pool)
        t.join();
}

FileMap filter_targets(const FileMap& all, const std::vector<Target>& targets) {
    FileMap kept;
    for (const auto& [path, bytes] : all)
        if (wanted(path, targets)) kept[path] = bytes;
    return kept;
}

BuildLedger::Hash128 BuildLedger::hash_of(std::string_view text) {
    const XXH128_hash_t h = XXH3_128bits(text.data(), text.size());
    return {h.high64, h.low64};
}

BuildLedger::BuildLedger() : name_lists(std::make_unique<NameLists>()) {}
BuildLedger::~BuildLedger() = default;

std::vector<JobResult> run_build_jobs(const Material& material, const std::vector<BuildJob>& jobs,
                                      const BuildOptions& options, StageCounts* stage_counts) {
    BuildLedger ledger;
    return run_build_jobs(material, JobList(jobs), 0, jobs, options, ledger, stage_counts);
}

std::vector<JobResult> run_build_jobs(const Material& material, const JobList& list, size_t begin,
                                      const std::vector<BuildJob>& batch,
                                      const BuildOptions& options, BuildLedger& ledger,
                                      StageCounts* stage_counts) {
    const size_t end = begin + batch.size();
    // Job i of the batch (begin <= i < end).
    auto job = [&](size_t i) -> const BuildJob& { return batch[i - begin]; };
    std::vector<JobResult> results(end - begin);
    auto result = [&](size_t i) -> JobResult& { return results[i - begin]; };
    // glslang builds its tables once per process; do it before the threads race for it.
    glslang_warm_up();

    StageMemo memo;
    const StageCompile compile{false, &memo};
    const EmitOptions emit =
        with_bindings(EmitOptions{false, {}, LoopUnroll::AsHinted, options.bindings});
    std::vector<StageKeys> stages(results.size());
    parallel_for(results.size(), options.threads, [&](size_t k) {
        compose_and_hash(material, batch[k], emit, compile, results[k], stages[k]);
    });
    const BuildPlan plan =
        plan_builds(list, begin, batch, results, ledger, static_cast<bool>(options.read_back));
    // The stages of the jobs that will compile, so the memo keeps those more than one shares.
    std::vector<StageKey> expected;
    for (size_t i : plan.to_build)
        for (const StageKey& key : stages[i - begin])
            if (!key.empty()) expected.push_back(key);
    std::vector<StageKeys>().swap(stages);
    memo.expect(std::move(expected));

    std::mutex progress_lock;
    BuildProgress& progress = ledger.progress;
    progress.total = list.size();
    auto report = [&](size_t i) {
        if (!options.progress) return;
        std::lock_guard<std::mutex> lock(progress_lock);
        ++progress.done;
        progress.cached += result(i).cached ? 1 : 0;
        progress.failed += result(i).ok() ? 0 : 1;
        progress.key = job_key(job(i));
        options.progress(progress);
    };
    for (size_t i = begin; i < end; ++i)
        if (!result(i).ok() || !result(i).same_as.empty()) report(i);

    // The jobs that take each built job's files (same content in another scene), done on the
    // builder's thread as soon as its files exist: nothing is kept for them.
    std::map<size_t, std::vector<size_t>> copies;
    for (const auto& [i, from] : plan.copies)
        copies[from].push_back(i);
    auto finish = [&](size_t i, const FileMap* all) {
        JobResult& r = result(i);
        if (all) r.files = filter_targets(*all, job(i).targets);
        std::vector<std::string> names;
        for (const auto& [name, bytes] : r.files)
            names.push_back(name);
        r.names = ledger.name_lists->intern(std::move(names));
        if (options.sink && r.ok()) options.sink(i, r);
        report(i);
    };
    // A tessellated variant writes its patch stages too.
    const std::array<std::vector<std::string>, 2> expected_files = {variant_file_names(false),
                                                                    variant_file_names(true)};
    parallel_for(plan.to_build.size(), options.threads, [&](size_t k) {
        const size_t i = plan.to_build[k];
        JobResult& r = result(i);
        const auto t0 = std::chrono::steady_clock::now();
        auto compose = [&] {
            Diagnostics composed; // reported in phase 1 already
            return compose_job(material, job(i), composed);
        };
        std::optional<FileMap> all =
            load_or_build(options, emit, compose, compile, r,
                          expected_files[job(i).variant.choice("geometry") == "tessellated"]);
        r.milliseconds =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count();
        finish(i, all ? &*all : nullptr);
        if (const auto it = copies.find(i); it != copies.end())
            for (size_t c : it->second) {
                result(c).diagnostics = r.diagnostics;
                result(c).cached = r.cached;
                result(c).shared = true;
                finish(c, all ? &*all : nullptr);
            }
    });
    // Files an earlier batch wrote, read back for the jobs of later scenes that take them.
    parallel_for(plan.borrowed.size(), options.threads, [&](size_t k) {
        const auto [i, from] = plan.borrowed[k];
        const auto it = ledger.built.find(hash_of(result(i).content_hash));
        std::optional<FileMap> all = options.read_back(from, *it->second.names);
        JobResult& r = result(i);
        if (all) {
            r.shared = true;
        } else {
            const BuildJob builder = list.at(from);
            r.diagnostics.push_back({Severity::Error, "", 0, 0, "",
                                     job(i).scene + ": " + job_key(job(i)) +
                                         ": cannot read back the files it shares with " +
                                         builder.scene + ": " + job_key(builder)});
        }
        finish(i, all ? &*all : nullptr);
    });
    // What later batches need of this one: the names of the files each first shape and each
    // content's builder wrote; and the files of each job that points at an earlier one.
    for (size_t i = begin; i < end; ++i) {
        JobResult& r = result(i);
        if (!r.ok()) continue;
        if (!r.same_as.empty()) {
            if (r.same_as_job >= begin) r.names = result(r.same_as_job).names;
            continue;
        }
        if (auto it = ledger.first.find(hash_of(r.shape_hash));
            it != ledger.first.end() && it->second.job == i)
            it->second.names = r.names;
        if (auto it = ledger.built.find(hash_of(r.content_hash));
            it != ledger.built.end() && it->second.job == i)
            it->second.names = r.names;
    }
    if (stage_counts) {
        const StageCounts counted = memo.counts();
        stage_counts->compiled += counted.compiled;
        stage_counts->reused += counted.reused;
    }
    return results;
}

} // namespace watergen
