#include "watergen/pipeline/build_output.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fcntl.h>

#include "watergen/ir/ir_fold.h"
#include "watergen/pipeline/build_record.h"
#include "watergen/pipeline/caustics_pass_build.h"
#include "watergen/pipeline/output_target.h"
#include "watergen/pipeline/output_writer.h"
#include "watergen/pipeline/safe_read.h"

namespace watergen {

namespace fs = std::filesystem;

namespace {

// The scene's jobs: one per variant, or one per shader of the mode.
void add_jobs(BuildPlan& plan, const std::string& scene, const std::vector<Variant>& variants,
              const FoldFacts* facts, const std::vector<Target>& targets, BuildMode mode) {
    if (mode == BuildMode::Permutations) {
        for (const Variant& v : variants)
            plan.jobs.push_back({scene, v, facts, targets});
        return;
    }
    for (const ShaderChoices& s : shaders_for(variants, mode)) {
        BuildJob job{scene, s.first_variant(), facts, targets, s, {}};
        for (const Variant& v : variants)
            if (s.covers(v)) job.serves.push_back(v);
        plan.jobs.push_back(std::move(job));
    }
}

} // namespace

VariantBuild build_for_scene(const Material& material, const ScenePlan& plan, const Variant& v) {
    WaterShader shader = material.compose(v);
    FoldResult folded = fold_graph(shader.fragment, plan.facts);
    shader.fragment = std::move(folded.graph);
    return build_shader(std::move(shader));
}

std::optional<BuildPlan> plan_build(const Material& material, const std::vector<SceneFacts>& scenes,
                                    Diagnostics& ds, BuildMode mode) {
    BuildPlan plan;
    std::vector<SceneFacts> sorted = scenes;
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const SceneFacts& a, const SceneFacts& b) { return a.name < b.name; });
    for (size_t i = 0; i < sorted.size(); ++i) {
        if (i > 0 && sorted[i].name == sorted[i - 1].name) {
            ds.push_back(sorted[i].where.error(
                "name", "scene name '" + sorted[i].name + "' is used by " + sorted[i - 1].file +
                            " too; expected one name per scene (it names a directory)"));
            return std::nullopt;
        }
        if (sorted[i].name == kUnprunedScene || sorted[i].name == kPassesDirectory) {
            ds.push_back(sorted[i].where.error("name", "scene name '" + sorted[i].name +
                                                           "' is reserved (" + kUnprunedScene +
                                                           ", " + kPassesDirectory + ")"));
            return std::nullopt;
        }
        auto p = plan_scene(material, sorted[i], ds);
        if (!p) return std::nullopt;
        plan.scenes.push_back(std::move(*p));
    }
    if (plan.scenes.empty()) {
        // Sorted by key, each key made once (the full space has 721,920: the count
        // the_full_space_has_721920_variants pins).
        std::vector<std::pair<std::string, Variant>> keyed;
        enumerate(material.space, [&](const Variant& v) { keyed.emplace_back(v.key(), v); });
        std::sort(keyed.begin(), keyed.end(),
                  [](const auto& a, const auto& b) { return a.first < b.first; });
        for (auto& [key, v] : keyed)
            plan.unpruned.push_back(std::move(v));
        add_jobs(plan, kUnprunedScene, plan.unpruned, nullptr, material.targets, mode);
        plan.manifest_scenes.push_back({kUnprunedScene, nullptr, plan.unpruned.size()});
    }
    for (const ScenePlan& s : plan.scenes) {
        add_jobs(plan, s.scene.name, s.variants, &s.facts, s.targets, mode);
        plan.manifest_scenes.push_back({s.scene.name, &s, s.variants.size()});
    }
    return plan;
}

namespace {

// Puts `staging` in the place of `dir` in one step: renameat2(RENAME_EXCHANGE) swaps the two
// names atomically, so whenever the process dies, `dir` holds either the old output or the
// new one, never nothing. Without an old output, a rename that replaces nothing; if a
// concurrent build creates `dir` in between, exchange with that. On file systems that cannot
// exchange, the two-rename commit of output_writer.h.
std::optional<std::string> swap_into_place(const fs::path& staging, const fs::path& dir) {
    for (int attempt = 0; attempt < 3; ++attempt) {
        if (::renameat2(AT_FDCWD, staging.c_str(), AT_FDCWD, dir.c_str(), RENAME_EXCHANGE) == 0) {
            remove_replaced_tree(staging); // the old output, now under the staging name
            return std::nullopt;
        }
        if (errno != ENOENT) break;
        if (::renameat2(AT_FDCWD, staging.c_str(), AT_FDCWD, dir.c_str(), RENAME_NOREPLACE) == 0)
            return std::nullopt;
        if (errno != EEXIST) break;
    }
    return commit_directory(staging, dir);
}

// A killed build leaves its staging directory ("<out>.tmp-<pid>", or "<out>.old.tmp-<pid>"
// from the fallback commit) beside the output; remove those whose process is gone.
void remove_stale_staging(const fs::path& out) {
    std::error_code ec;
    const fs::path parent = out.parent_path().empty() ? fs::path(".") : out.parent_path();
    const std::string name = out.filename().string();
    std::vector<fs::path> stale;
    for (const auto& e : fs::directory_iterator(parent, ec)) {
        const std::string entry = e.path().filename().string();
        for (const std::string& prefix : {name + ".tmp-", name + ".old.tmp-"}) {
            if (entry.rfind(prefix, 0) != 0) continue;
            const std::string digits = entry.substr(prefix.size());
            if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos)
                continue;
            const long pid = std::stol(digits);
            if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)
                stale.push_back(e.path());
        }
    }
    for (const auto& p : stale)
        fs::remove_all(p, ec);
}

// The output directory, resolved, if a build may replace it; else "" and the refusal in `s`.
fs::path accepted_output(const fs::path& out, BuildSummary& s,
                         const std::vector<std::string>& recorded = {}) {
    const OutputTarget target = check_output_target(out, recorded);
    if (target.ok()) return target.path;
    s.bad_input = true;
    s.diagnostics.push_back({Severity::Error, out.string(), 0, 0, "", target.error});
    return {};
}

// Writes `files` beside the output directory `out` and swaps them in.
std::optional<std::string> publish(const fs::path& out,
                                   const std::map<std::string, std::string>& files) {
    // Staging beside the output, then one rename: readers never see a mix of two builds.
    remove_stale_staging(out);
    std::string error;
    const fs::path staging = write_staged_tree(out, files, &error);
    if (staging.empty()) return error;
    return swap_into_place(staging, out);
}

// Counts a job's result in the summary.
void count(const BuildJob& job, const JobResult& r, const BuildCache& cache, BuildSummary& s) {
    if (!r.cache_rejected.empty()) {
        ++s.cache_rejected;
        s.diagnostics.push_back(cache.rejected_warning(r.content_hash, r.cache_rejected));
    }
    if (!r.ok()) {
        ++s.failed;
        for (const auto& d : r.diagnostics)
            s.diagnostics.push_back(d);
        s.diagnostics.push_back(
            {Severity::Error, "", 0, 0, "", job.scene + ": " + job_key(job) + " failed to build"});
        return;
    }
    if (!r.same_as.empty()) {
        ++s.same;
        return;
    }
    (r.shared ? s.shared : r.cached ? s.cached : s.built) += 1;
}

// Moves a job's files (under its variant directory) into the output, once everything that
// reads them (frozen modules, the manifest) has: the bytes are not held twice.
void move_files(const BuildJob& job, JobResult& r, std::map<std::string, std::string>& files) {
    if (!r.ok() || !r.same_as.empty()) return;
    const std::string dir = job_directory(job);
    for (auto& [path, bytes] : r.files)
        files[dir + "/" + path] = std::move(bytes);
    r.files.clear();
}

// Specialized mode with freeze: each variant's SPIR-V (both language paths) with the shader's
// selectors frozen to the variant's values, beside the shader's own.
void add_frozen(const std::vector<BuildJob>& jobs, const std::vector<JobResult>& results,
                const BuildOptions& options, BuildSummary& s,
                std::map<std::string, std::string>& files) {
    struct Work {
        size_t job;
        Variant variant;
        std::string lang;
    };
    std::vector<Work> work;
    for (size_t i = 0; i < jobs.size(); ++i)
        if (jobs[i].shader && results[i].ok() && results[i].same_as.empty())
            for (const Variant& v : jobs[i].serves)
                for (const char* lang : {"glsl", "hlsl"})
                    if (results[i].files.count(std::string(lang) + "/water.frag.opt.spv"))
                        work.push_back({i, v, lang});
    std::vector<FrozenVariant> frozen(work.size());
    parallel_for(work.size(), options.threads, [&](size_t k) {
        const Work& w = work[k];
        frozen[k] =
            freeze_variant(results[w.job], *jobs[w.job].shader, w.variant, w.lang, options.cache);
    });
    for (size_t k = 0; k < work.size(); ++k) {
        const Work& w = work[k];
        const std::string path = job_directory(jobs[w.job]) + "/" + frozen_path(w.lang, w.variant);
        if (!frozen[k].cache_rejected.empty()) {
            ++s.cache_rejected;
            s.diagnostics.push_back(
                options.cache.rejected_warning(frozen[k].content_hash, frozen[k].cache_rejected));
        }
        ++s.frozen;
        s.frozen_cached += frozen[k].cached ? 1 : 0;
        if (frozen[k].spirv.empty()) {
            ++s.failed;
            s.diagnostics.insert(s.diagnostics.end(), frozen[k].diagnostics.begin(),
                                 frozen[k].diagnostics.end());
            s.diagnostics.push_back({Severity::Error, path, 0, 0, "", "freezing failed"});
            continue;
        }
        files[path] = std::move(frozen[k].spirv);
    }
}

} // namespace

namespace {

// The summary of a build that found its record matching and its output intact; nullopt when
// it must run.
std::optional<BuildSummary> up_to_date(const BuildRequest& request, const std::string& key,
                                       const fs::path& record) {
    const auto r = read_record(record);
    if (!r || r->key != key || !outputs_intact(request.out, *r, request.options.threads))
        return std::nullopt;
    // Intact as recorded, manifest.json included; the record must also name what it names.
    const SafeRead manifest =
        read_regular_file(normal_output_path(request.out) / "manifest.json", kMaxManifestBytes);
    if (!manifest.bytes || !record_covers_manifest(*r, *manifest.bytes)) return std::nullopt;
    BuildSummary s;
    s.up_to_date = true;
    s.variants = r->variants;
    s.shaders = r->shaders;
    s.files = r->files.size();
    return s;
}

// The plan's jobs of the shard only (the plan's scenes stay whole: the manifest counts them).
void keep_shard(BuildPlan& plan, const Shard& shard) {
    std::vector<BuildJob> kept;
    for (BuildJob& job : plan.jobs)
        if (in_shard(shard, job_key(job))) kept.push_back(std::move(job));
    plan.jobs = std::move(kept);
}

} // namespace

std::optional<BuildSummary> build_up_to_date(const BuildRequest& request) {
    const auto t0 = std::chrono::steady_clock::now();
    if (request.inputs_hash.empty() || !request.options.cache.enabled()) return std::nullopt;
    auto done = up_to_date(request, record_key(request.inputs_hash, shard_text(request.shard)),
                           record_file(request.options.cache, request.out));
    if (done)
        done->seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return done;
}

BuildSummary build_material(const BuildRequest& request) {
    // Nothing changed and the output is intact: no IR work, the output untouched.
    if (auto done = build_up_to_date(request)) return *done;
    return build_material_now(request);
}

BuildSummary build_material_now(const BuildRequest& request) {
    const auto t0 = std::chrono::steady_clock::now();
    auto elapsed = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };
    const bool recorded = !request.inputs_hash.empty() && request.options.cache.enabled();
    const std::string key =
        recorded ? record_key(request.inputs_hash, shard_text(request.shard)) : "";
    const fs::path record = recorded ? record_file(request.options.cache, request.out) : fs::path();
    BuildSummary s;
    if (request.shard.sharded() && request.mode != BuildMode::Permutations) {
        s.bad_input = true;
        s.diagnostics.push_back({Severity::Error, "", 0, 0, "",
                                 "--shard: shards permutations builds; expected --mode "
                                 "permutations, got --mode " +
                                     std::string(to_string(request.mode))});
        return s;
    }
    auto plan = plan_build(request.material, request.scenes, s.diagnostics, request.mode);
    if (!plan) {
        s.bad_input = true;
        return s;
    }
    if (request.shard.sharded()) keep_shard(*plan, request.shard);
    // Refuse an output that is not ours before spending time on the build.
    std::vector<std::string> written; // what the last build into request.out wrote
    if (const auto last = recorded ? read_record(record) : std::nullopt)
        for (const RecordedFile& f : last->files)
            written.push_back(f.path);
    if (accepted_output(request.out, s, written).empty()) return s;
    std::vector<JobResult> results = run_build_jobs(request.material, plan->jobs, request.options);
    s.shaders = plan->jobs.size();
    for (const BuildJob& job : plan->jobs)
        s.variants += job.shader ? job.serves.size() : 1;
    std::map<std::string, std::string> files;
    for (size_t i = 0; i < results.size(); ++i)
        count(plan->jobs[i], results[i], request.options.cache, s);
    if (request.freeze && request.mode == BuildMode::Specialized)
        add_frozen(plan->jobs, results, request.options, s, files);
    // The companion passes the built variants draw with, each once for the whole output.
    PassesOutput passes =
        build_needed_passes(request.material, plan->jobs, results, request.options);
    s.passes = passes.passes.size();
    s.passes_cached = passes.cached;
    s.cache_rejected += passes.cache_rejected.size();
    s.diagnostics.insert(s.diagnostics.end(), passes.cache_rejected.begin(),
                         passes.cache_rejected.end());
    s.failed += passes.failed;
    s.diagnostics.insert(s.diagnostics.end(), passes.diagnostics.begin(), passes.diagnostics.end());
    files.merge(passes.files);
    if (s.failed == 0) {
        files["manifest.json"] =
            request.mode == BuildMode::Permutations
                ? manifest_json(request.material, plan->manifest_scenes, plan->jobs, results,
                                passes.passes)
                : modes_manifest_json(request.material, request.mode, request.freeze,
                                      plan->manifest_scenes, plan->jobs, results, passes.passes);
        for (size_t i = 0; i < results.size(); ++i)
            move_files(plan->jobs[i], results[i], files);
        if (request.shard.sharded())
            files[kShardFile] = shard_json(request.shard, request.inputs_hash, plan->jobs, results,
                                           s.variants, files);
        s.files = files.size();
        if (auto failure = publish_output(request.out, files, written))
            s.diagnostics.push_back({Severity::Error, request.out.string(), 0, 0, "", *failure});
        else if (recorded)
            store_record(record, make_record(key, s.variants, s.shaders, files));
    }
    s.seconds = elapsed();
    return s;
}

std::optional<std::string> publish_output(const fs::path& out, const FileMap& files,
                                          const std::vector<std::string>& recorded) {
    BuildSummary refused;
    const fs::path resolved = accepted_output(out, refused, recorded); // again: it took a while
    if (resolved.empty()) return refused.diagnostics.front().message;
    return publish(resolved, files);
}

} // namespace watergen
