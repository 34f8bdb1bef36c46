#include "watergen/pipeline/build/build_output.h"
#include "watergen/pipeline/record/shaders_header.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <set>

#include "watergen/ir/fold/ir_fold.h"
#include "watergen/pipeline/manifest/caustics_pass_build.h"
#include "watergen/pipeline/output/output_target.h"
#include "watergen/pipeline/output/output_writer.h"
#include "watergen/pipeline/output/safe_read.h"
#include "watergen/pipeline/record/build_record.h"
#include "watergen/pipeline/record/staged_tree.h"
#include "watergen/plan/shader_fold.h"

namespace watergen {

namespace fs = std::filesystem;

namespace {

// The combination of the permutation-only axes' choices that `v` makes: its shader's, of those
// shaders_for() makes in the specialized and branching modes.
std::string fixed_choices(const Variant& v) {
    std::string fixed;
    for (size_t a = 0; a < axes().size(); ++a)
        if (permutation_only(axes()[a].name)) fixed += v.choices[a] + ",";
    return fixed;
}

// The scene's jobs of the shard in a mode: one per shader, each with the variants it serves,
// kept a byte an axis (`variants`, sorted by key).
void add_shader_jobs(BuildPlan& plan, const std::string& scene, const VariantList& variants,
                     const FoldFacts* facts, const std::vector<Target>& targets, BuildMode mode,
                     const Shard& shard) {
    // shaders_for() offers each shader the choices its variants make: per combination of the
    // permutation-only axes, each choice made on each axis, by one variant each.
    std::map<std::string, std::pair<Variant, std::vector<std::set<std::string>>>> groups;
    Variant v = default_variant();
    for (size_t i = 0; i < variants.size(); ++i) {
        variants.fill(i, v);
        auto [it, fresh] = groups.try_emplace(fixed_choices(v), v, axes().size());
        for (size_t a = 0; a < axes().size(); ++a)
            it->second.second[a].insert(v.choices[a]);
    }
    std::vector<Variant> representatives;
    for (const auto& [fixed, group] : groups)
        for (size_t a = 0; a < axes().size(); ++a)
            for (const std::string& choice : group.second[a]) {
                representatives.push_back(group.first);
                representatives.back().choices[a] = choice;
            }
    const std::vector<ShaderChoices> shaders = shaders_for(representatives, mode);
    std::map<std::string, size_t> shader_of; // fixed choices -> shader
    std::vector<std::shared_ptr<VariantList>> serves(shaders.size());
    for (size_t k = 0; k < shaders.size(); ++k) {
        shader_of[fixed_choices(shaders[k].first_variant())] = k;
        if (!shard.sharded() || in_shard(shard, shaders[k].key()))
            serves[k] = std::make_shared<VariantList>(variants.choices());
    }
    for (size_t i = 0; i < variants.size(); ++i) {
        variants.fill(i, v);
        if (const auto& list = serves[shader_of.at(fixed_choices(v))]) list->add_from(variants, i);
    }
    for (size_t k = 0; k < shaders.size(); ++k)
        if (serves[k])
            plan.jobs.push_back(
                {scene, shaders[k].first_variant(), facts, targets, shaders[k], serves[k]});
}

} // namespace

VariantBuild build_for_scene(const Material& material, const ScenePlan& plan, const Variant& v) {
    WaterShader shader = material.compose(v);
    fold_water_shader(shader, plan.facts);
    return build_shader(std::move(shader));
}

std::optional<BuildPlan> plan_build(const Material& material, const std::vector<SceneFacts>& scenes,
                                    Diagnostics& ds, BuildMode mode, const Shard& shard) {
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
        // Sorted by key, each key made once (the full space has 3,502,080: the count
        // the_full_space_has_3502080_variants pins). A permutations shard keeps its own only:
        // the whole space's jobs would be most of a shard's memory.
        size_t count = 0;
        if (mode == BuildMode::Permutations) {
            plan.jobs = JobList::compact(kUnprunedScene, material.space, material.targets,
                                         [&](const std::string& key) {
                                             ++count;
                                             return !shard.sharded() || in_shard(shard, key);
                                         });
        } else {
            VariantList unpruned(material.space.choices);
            enumerate_indices(material.space,
                              [&](const std::vector<size_t>& index) { unpruned.add(index); });
            unpruned.sort_by_key();
            count = unpruned.size();
            add_shader_jobs(plan, kUnprunedScene, unpruned, nullptr, material.targets, mode, shard);
        }
        plan.manifest_scenes.push_back({kUnprunedScene, nullptr, count});
    }
    for (const ScenePlan& s : plan.scenes) {
        if (mode == BuildMode::Permutations)
            plan.jobs.add_scene(
                s.scene.name, s.variants, &s.facts, s.targets,
                [&](const std::string& key) { return !shard.sharded() || in_shard(shard, key); });
        else
            add_shader_jobs(plan, s.scene.name, s.variants, &s.facts, s.targets, mode, shard);
        plan.manifest_scenes.push_back({s.scene.name, &s, s.variants.size()});
    }
    return plan;
}

namespace {

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
    return swap_directory_into_place(staging, out);
}

// Counts a job's result in the summary.
void count(const BuildJob& job, const JobResult& r, const BuildOptions& options, BuildSummary& s) {
    const BuildCache& cache = options.cache;
    if (!r.cache_rejected.empty()) {
        ++s.cache_rejected;
        s.diagnostics.push_back(cache.rejected_warning(r.content_hash, r.cache_rejected));
    }
    if (!r.ok()) {
        // A failure only on what the binding map cannot give is bad input (exit 2), the map
        // being an input; one failure of another kind makes the build a failed one.
        const bool map = only_binding_map_errors(r.diagnostics, options.bindings);
        s.bad_input = s.failed == 0 ? map : s.bad_input && map;
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

// The first error of the writes into the staging tree (a full disk): the build then fails
// with it and publishes nothing.
struct WriteErrors {
    std::mutex lock;
    std::optional<std::string> first;
    void note(std::optional<std::string> e) {
        if (!e) return;
        std::lock_guard<std::mutex> guard(lock);
        if (!first) first = std::move(e);
    }
    bool any() {
        std::lock_guard<std::mutex> guard(lock);
        return first.has_value();
    }
};

// Writes a job's files under its directory into the tree as soon as they exist, and lets them go.
// `batch`: the jobs of the batch being run, the first of them job `begin`.
std::function<void(size_t, JobResult&)> job_sink(const std::vector<BuildJob>& batch,
                                                 const size_t& begin, StagedTree& tree,
                                                 WriteErrors& errors) {
    return [&batch, &begin, &tree, &errors](size_t i, JobResult& r) {
        const std::string dir = job_directory(batch[i - begin]);
        for (const auto& [path, bytes] : r.files)
            errors.note(tree.write(dir + "/" + path, bytes));
        r.files.clear();
        // Only a failed job's diagnostics reach the summary, and a sunk job did not fail: its
        // notes (a skipped GL target per stage, each naming its file) would be kept for nothing.
        Diagnostics().swap(r.diagnostics);
    };
}

// Specialized mode with freeze: each variant's SPIR-V (both language paths) with the shader's
// selectors frozen to the variant's values, beside the shader's own (read back from the tree).
void add_frozen(const std::vector<BuildJob>& jobs, const std::vector<JobResult>& results,
                const BuildOptions& options, BuildSummary& s, StagedTree& tree,
                WriteErrors& errors) {
    struct Work {
        size_t job, built; // the variant's shader and the one whose module it has
        Variant variant;
        std::string lang;
    };
    // A shader with the same shape as another's of its scene is that one's module: its
    // variants are frozen from it, beside its own, where the manifest points them.
    std::vector<Work> work;
    for (size_t i = 0; i < jobs.size(); ++i) {
        if (!jobs[i].shader || !results[i].ok()) continue;
        const size_t built = results[i].files_of(i);
        for (size_t k = 0; k < jobs[i].serves->size(); ++k)
            for (const char* lang : {"glsl", "hlsl"})
                if (const auto& names = results[built].file_names(); std::binary_search(
                        names.begin(), names.end(), std::string(lang) + "/water.frag.opt.spv"))
                    work.push_back({i, built, jobs[i].serves->at(k), lang});
    }
    std::vector<FrozenVariant> frozen(work.size());
    std::vector<char> failed(work.size(), 0);
    parallel_for(work.size(), options.threads, [&](size_t k) {
        const Work& w = work[k];
        const std::string dir = job_directory(jobs[w.built]) + "/";
        const auto module = tree.read(dir + w.lang + "/water.frag.opt.spv");
        const auto description = tree.read(dir + "variant.json");
        if (!module || !description) {
            frozen[k].diagnostics.push_back(
                {Severity::Error, dir + w.lang, 0, 0, "", "cannot read the built module back"});
            failed[k] = 1;
            return;
        }
        frozen[k] = freeze_variant(*module, *description, *jobs[w.job].shader, w.variant, w.lang,
                                   options.cache);
        if (frozen[k].spirv.empty()) {
            failed[k] = 1;
            return;
        }
        errors.note(tree.write(dir + frozen_path(w.lang, w.variant), frozen[k].spirv));
        frozen[k].spirv = std::string(); // written: not held
    });
    for (size_t k = 0; k < work.size(); ++k) {
        const Work& w = work[k];
        const std::string path =
            job_directory(jobs[w.built]) + "/" + frozen_path(w.lang, w.variant);
        if (!frozen[k].cache_rejected.empty()) {
            ++s.cache_rejected;
            s.diagnostics.push_back(
                options.cache.rejected_warning(frozen[k].content_hash, frozen[k].cache_rejected));
        }
        ++s.frozen;
        s.frozen_cached += frozen[k].cached ? 1 : 0;
        if (failed[k]) {
            ++s.failed;
            s.diagnostics.insert(s.diagnostics.end(), frozen[k].diagnostics.begin(),
                                 frozen[k].diagnostics.end());
            s.diagnostics.push_back({Severity::Error, path, 0, 0, "", "freezing failed"});
        }
    }
}

// The summary of a build that found its record matching and its output intact; nullopt when
// it must run.
std::optional<BuildSummary> up_to_date(const BuildRequest& request, const std::string& key,
                                       const fs::path& record) {
    // Read a slice of files at a time: a large build's record is larger than its memory should be.
    const auto r = read_record_head(record);
    if (!r || r->key != key || !outputs_intact(request.out, record, request.options.threads))
        return std::nullopt;
    // Intact as recorded, manifest.json included; the record must also name what it names.
    SafeRead seen;
    std::FILE* manifest =
        open_regular_stream(normal_output_path(request.out) / "manifest.json", seen);
    if (!manifest) return std::nullopt;
    // The header (or a shard's shard.json) is not among the manifest's files: the record must
    // vouch for it too, or a header deleted since would stay missing.
    const bool covered = record_covers_manifest(
        record, manifest, record.parent_path(),
        {request.shard.sharded() ? std::string(kShardFile) : std::string(kShadersHeader)});
    std::fclose(manifest);
    if (!covered) return std::nullopt;
    BuildSummary s;
    s.up_to_date = true;
    s.variants = r->variants;
    s.shaders = r->shaders;
    s.files = r->files;
    return s;
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
    auto plan =
        plan_build(request.material, request.scenes, s.diagnostics, request.mode, request.shard);
    if (!plan) {
        s.bad_input = true;
        return s;
    }
    // Refuse an output that is not ours before spending time on the build. `written`: the first
    // component of each file the last build into request.out wrote there.
    std::vector<std::string> written;
    if (auto tops = recorded ? record_top_entries(record) : std::nullopt)
        written = std::move(*tops);
    const fs::path out = accepted_output(request.out, s, written);
    if (out.empty()) return s;
    // Every file goes to a staging tree beside the output as soon as it is built; the tree
    // replaces the output at the end, or is removed.
    std::string error;
    const std::unique_ptr<StagedTree> tree = StagedTree::open(out, &error);
    if (!tree) {
        s.diagnostics.push_back({Severity::Error, request.out.string(), 0, 0, "", error});
        return s;
    }
    WriteErrors errors;
    BuildOptions options = request.options;
    std::vector<BuildJob> batch; // the jobs being run, from job `begin` on
    size_t begin = 0;
    // Job i, of the batch or (made again from the list) of an earlier one.
    auto job_at = [&](size_t i) {
        return i >= begin && i - begin < batch.size() ? batch[i - begin] : plan->jobs.at(i);
    };
    options.sink = job_sink(batch, begin, *tree, errors);
    options.read_back = [&](size_t job,
                            const std::vector<std::string>& names) -> std::optional<FileMap> {
        const std::string dir = job_directory(plan->jobs.at(job)) + "/";
        FileMap files;
        for (const std::string& name : names) {
            auto bytes = tree->read(dir + name);
            if (!bytes) return std::nullopt;
            files[name] = std::move(*bytes);
        }
        return files;
    };
    // A permutations build writes its manifest, and shard.json's shapes, a batch of jobs at a
    // time: memory holds one batch's jobs and results. A modes build's manifest lists each
    // shader's variants across shaders: it holds every result (its jobs are shaders, far fewer).
    const bool streamed = request.mode == BuildMode::Permutations;
    s.shaders = plan->jobs.size();
    s.variants = plan->jobs.size();
    if (!streamed) {
        s.variants = 0;
        for (const BuildJob& job : plan->jobs.held())
            s.variants += job.shader ? job.serves->size() : 1;
    }
    // The companion passes the variants draw with, each once for the whole output; first, as
    // the manifest's entries point at them.
    PassesOutput passes = build_needed_passes(request.material, plan->jobs, request.options);
    s.passes = passes.passes.size();
    s.passes_cached = passes.cached;
    s.cache_rejected += passes.cache_rejected.size();
    s.diagnostics.insert(s.diagnostics.end(), passes.cache_rejected.begin(),
                         passes.cache_rejected.end());
    s.failed += passes.failed;
    // A build that fails only on what the binding map cannot give is refused as bad input.
    s.bad_input = passes.failed > 0 && passes.failed == passes.failed_by_map;
    s.diagnostics.insert(s.diagnostics.end(), passes.diagnostics.begin(), passes.diagnostics.end());
    for (const auto& [path, bytes] : passes.files)
        errors.note(tree->write(path, bytes));
    FileMap().swap(passes.files);

    const ReadJobFile read = [&](size_t job, const std::string& name) {
        return tree->read(job_directory(job_at(job)) + "/" + name);
    };
    StagedStream manifest = tree->stream("manifest.json");
    const WriteText write = [&](std::string_view piece) { manifest.write(piece); };
    std::optional<ManifestWriter> entries;
    if (streamed)
        entries.emplace(request.material, plan->manifest_scenes, passes.passes, read, write,
                        request.options.bindings);
    std::optional<StagedStream> shard_stream;
    std::optional<ShardJsonWriter> shard_json;
    if (request.shard.sharded()) {
        shard_stream.emplace(tree->stream(kShardFile));
        shard_json.emplace(request.shard, request.inputs_hash, s.variants,
                           [&](std::string_view piece) { shard_stream->write(piece); });
    }
    BuildLedger ledger;
    std::vector<JobResult> held; // a modes build's
    const size_t batch_jobs =
        std::max<size_t>(streamed ? request.batch_jobs : plan->jobs.size(), 1);
    // A write that failed (a full disk) ends the build after its batch: nothing is published,
    // and the files the manifest would read back from the tree may be cut short.
    for (begin = 0; begin < plan->jobs.size() && !errors.any(); begin += batch_jobs) {
        batch = plan->jobs.range(begin, std::min(begin + batch_jobs, plan->jobs.size()));
        std::vector<JobResult> results =
            run_build_jobs(request.material, plan->jobs, begin, batch, options, ledger, &s.stages);
        const bool written = !errors.any();
        for (size_t k = 0; k < batch.size(); ++k) {
            const JobResult& r = results[k];
            count(batch[k], r, request.options, s);
            // Nothing is published after a failure: the rest is not written.
            if (s.failed > 0 || !written) continue;
            if (entries)
                entries->add(batch[k], r, r.files_of(begin + k), job_at(r.files_of(begin + k)));
            if (shard_json) shard_json->add(batch[k], r);
        }
        if (!streamed) held = std::move(results);
    }
    if (request.freeze && request.mode == BuildMode::Specialized && !errors.first)
        add_frozen(plan->jobs.held(), held, request.options, s, *tree, errors);
    const ListFiles list_files = [&](const std::function<void(const RecordedFile&)>& each) {
        tree->for_each_file(each);
    };
    if (s.failed == 0 && !errors.first) {
        if (entries)
            entries->end();
        else
            write_modes_manifest(request.material, request.mode, request.freeze,
                                 plan->manifest_scenes, plan->jobs.held(), held, passes.passes,
                                 read, write, request.options.bindings);
        errors.note(manifest.close());
        // The build's C++ header, from what it wrote; a shard's comes from the merge instead.
        if (!request.shard.sharded() && !errors.first) errors.note(write_shaders_header(*tree));
        if (shard_json && !errors.first) {
            // Lists every file so far: shard.json is recorded once it is closed.
            shard_json->end(list_files);
            errors.note(shard_stream->close());
        }
    }
    if (errors.first)
        s.diagnostics.push_back({Severity::Error, request.out.string(), 0, 0, "", *errors.first});
    if (s.failed == 0 && !errors.first) {
        s.files = tree->count();
        BuildSummary refused;
        const fs::path target = accepted_output(request.out, refused, written); // it took a while
        if (target.empty())
            s.diagnostics.push_back(refused.diagnostics.front());
        else if (auto failure = tree->commit(target))
            s.diagnostics.push_back({Severity::Error, request.out.string(), 0, 0, "", *failure});
        else if (recorded)
            if (auto why = store_record(record, key, s.variants, s.shaders, s.files, list_files))
                s.diagnostics.push_back(
                    {Severity::Warning, record.string(), 0, 0, "", record_not_stored(*why)});
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
