#include "watergen/pipeline/manifest/manifest.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <queue>
#include <set>
#include <tuple>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "watergen/ir/emit/emitter.h"
#include "watergen/pipeline/output/json_document.h"
#include "watergen/plan/binding_map_file.h"
#include "watergen/runtime/manifest_schema.h"
#include "watergen/toolchain/spirv_tools_stage.h"
#include "watergen/water/binding_profiles.h"

namespace watergen {

namespace mk = manifest_schema;

std::string variant_directory(const std::string& scene, const Variant& v) {
    return scene + "/" + v.file_stem();
}

namespace {

using OJson = nlohmann::ordered_json;

// Facts as text only: their file positions depend on how the files were named on the
// command line, and the manifest must not.
std::vector<std::string> fact_texts(const FoldFacts* facts, const FactSet& set) {
    std::vector<std::string> out;
    if (!facts) return out;
    for (size_t i = 0; i < facts->facts.size() && i < kMaxFacts; ++i)
        if (set.test(i)) out.push_back(facts->facts[i].text);
    return out;
}

OJson material_json(const Material& m) {
    OJson j;
    j[mk::material::kName] = m.name;
    j[mk::material::kDescription] = m.description;
    j[mk::material::kPreset] = m.preset;
    OJson ax = OJson::object();
    for (size_t i = 0; i < axes().size(); ++i)
        ax[axes()[i].name] = m.space.choices[i];
    j[mk::material::kAxes] = ax;
    OJson rules = OJson::array();
    const size_t builtin = builtin_rules().size();
    for (size_t i = builtin; i < m.space.rules.size(); ++i) {
        const Rule& r = m.space.rules[i];
        rules.push_back(
            {{mk::rule::kIf, r.axis + "=" + r.choice},
             {r.kind == Rule::Kind::Requires ? mk::rule::kRequires : mk::rule::kExcludes,
              {{r.other_axis, r.other_choices}}},
             {mk::rule::kWhy, r.why}});
    }
    j[mk::material::kRules] = rules;
    OJson params = OJson::object();
    for (const auto& [name, s] : m.parameters) {
        OJson p = OJson::object();
        if (s.value) p[mk::parameter::kValue] = *s.value;
        if (s.min) p[mk::parameter::kMin] = *s.min;
        if (s.max) p[mk::parameter::kMax] = *s.max;
        params[name] = p;
    }
    j[mk::material::kParameters] = params;
    OJson targets = OJson::array();
    for (Target t : m.targets)
        targets.push_back(to_string(t));
    j[mk::material::kTargets] = targets;
    return j;
}

OJson scene_json(const ManifestScene& s) {
    OJson j;
    j[mk::scene::kName] = s.name;
    if (!s.plan) {
        j[mk::scene::kPruned] = false;
        j[mk::scene::kVariants] = s.variants;
        return j;
    }
    const SceneFacts& f = s.plan->scene;
    j[mk::scene::kPruned] = true;
    j[mk::scene::kDescription] = f.description;
    j[mk::scene::kFile] = f.file;
    OJson facts = OJson::object();
    for (const SceneKey& k : scene_keys())
        if (k.manifest)
            if (OJson value = k.manifest(f); !value.is_null()) facts[std::string(k.key)] = value;
    j[mk::scene::kFacts] = facts;
    j[mk::scene::kVariants] = s.plan->variants.size();
    j[mk::scene::kSkipped] = s.plan->skipped;
    OJson fixed = OJson::object();
    for (const auto& [name, v] : s.plan->fixed)
        fixed[name] = v;
    j[mk::scene::kFixed] = fixed;
    OJson targets = OJson::array();
    for (Target t : s.plan->targets)
        targets.push_back(to_string(t));
    j[mk::scene::kTargets] = targets;
    return j;
}

// What folding did to the job's shader.
void add_fold(OJson& v, const BuildJob& job, const JobResult& r) {
    OJson folded = OJson::object();
    for (const auto& [name, value] : r.fold.folded_parameters)
        folded[name] = value;
    v[mk::fold::kFoldedParameters] = folded;
    if (!r.folded) return;
    OJson removed_params = OJson::array(), removed_textures = OJson::array(),
          terms = OJson::array();
    for (const auto& p : r.fold.removed_parameters)
        removed_params.push_back({{mk::removed::kName, p.name},
                                  {mk::removed::kBecause, fact_texts(job.facts, p.facts)}});
    for (const auto& t : r.fold.removed_textures)
        removed_textures.push_back({{mk::removed::kName, t.name},
                                    {mk::removed::kBecause, fact_texts(job.facts, t.facts)}});
    for (const auto& t : r.fold.removed)
        if (t.named) {
            const FactSet fs =
                t.event >= 0 ? r.fold.events[static_cast<size_t>(t.event)].facts : FactSet{};
            terms.push_back({{mk::removed::kNode, t.origin},
                             {mk::removed::kTerm, t.name},
                             {mk::removed::kBecause, fact_texts(job.facts, fs)}});
        }
    v[mk::fold::kRemovedParameters] = removed_params;
    v[mk::fold::kRemovedTextures] = removed_textures;
    v[mk::fold::kRemovedTerms] = terms;
    v[mk::fold::kLiveIrNodes] = {{mk::live_ir_nodes::kBefore, r.fold.live_before},
                                 {mk::live_ir_nodes::kAfter, r.fold.live_after}};
}

// Where the job's files are (its own, or those of `built_job`, the earlier job with the same
// shader, which `r` names), its reflection and SPIR-V counts.
void add_output(OJson& v, const JobResult& r, size_t built, const BuildJob& built_job,
                const ReadJobFile& read) {
    if (!r.same_as.empty()) v[mk::output::kSameAs] = r.same_as;
    v[mk::output::kDirectory] = job_directory(built_job);
    v[mk::output::kFiles] = files_json(job_directory(built_job), r.file_names());
    if (const auto description = read(built, "variant.json")) {
        // variant.json holds these at its top level, under the keys the manifest gives them.
        namespace refl = mk::reflection;
        const OJson d = OJson::parse(*description);
        v[mk::output::kReflection] = {
            {refl::kUniformBlock, d.value(refl::kUniformBlock, OJson::object())},
            {refl::kSampler, d.value(refl::kSampler, OJson::object())},
            {refl::kTextures, d.value(refl::kTextures, OJson::array())}};
        if (d.contains(refl::kSpecializationConstants))
            v[mk::output::kReflection][refl::kSpecializationConstants] =
                d[refl::kSpecializationConstants];
        v[mk::output::kSpirvInstructions] =
            d.value(mk::output::kSpirvInstructions, OJson::object());
        // A mesh variant's stages, vertex layout and grid (variant.json's "geometry").
        if (d.contains(mk::output::kGeometry)) v[mk::output::kGeometry] = d[mk::output::kGeometry];
    }
}

// The map's name as the manifest gives it: a profile's, or its file's (not the path, which
// differs between machines that build the same inputs).
std::string map_name(const BindingMap& map) {
    return binding_profile(map.name) ? map.name
                                     : std::filesystem::path(map.name).filename().string();
}

OJson header_json(const Material& material, const std::vector<ManifestScene>& scenes,
                  const BindingMap* bindings) {
    const BindingMap& map = bindings ? *bindings : default_binding_map();
    OJson doc;
    doc[mk::top::kGenerator] = std::string(mk::top::kGeneratorPrefix) + WATERGEN_VERSION;
    doc[mk::top::kMaterial] = material_json(material);
    doc[mk::top::kSpace] = {{mk::space::kFull, count_variants(full_space())},
                            {mk::space::kMaterial, count_variants(material.space)}};
    OJson sc = OJson::array();
    for (const auto& s : scenes)
        sc.push_back(scene_json(s));
    doc[mk::top::kScenes] = sc;
    // The map's resources as its file spells them (binding_map_file.cpp), without the file's
    // version.
    OJson b = binding_map_json(map);
    b.erase("watergen_bindings");
    doc[mk::top::kBindings] = {{mk::bindings::kMap, map_name(map)},
                               {mk::bindings::kResources, b[mk::bindings::kResources]}};
    if (b.contains(mk::bindings::kPushConstantBytes))
        doc[mk::top::kBindings][mk::bindings::kPushConstantBytes] =
            b[mk::bindings::kPushConstantBytes];
    return doc;
}

// "passes", for a variant drawn with a companion pass (last: a merge copies it with the files).
void add_passes(OJson& v, const Material& material, const Variant& variant, const BuildJob& job,
                const JobResult& r, const CausticsPasses& passes) {
    OJson entry = passes_entry(material, variant, job.targets, r.fold.folded_parameters, passes);
    if (!entry.is_null()) v[mk::variant::kPasses] = std::move(entry);
}

OJson nodes_json(const Variant& v) {
    OJson nodes = OJson::object();
    for (const auto& a : axes())
        nodes[a.name] = a.name + "." + v.choice(a.name);
    return nodes;
}

} // namespace

OJson files_json(const std::string& dir, const FileMap& files) {
    std::vector<std::string> names;
    for (const auto& [path, bytes] : files)
        names.push_back(path);
    return files_json(dir, names);
}

OJson files_json(const std::string& dir, const std::vector<std::string>& names) {
    OJson j = OJson::object();
    std::map<std::string, std::vector<std::string>> by;
    for (const std::string& path : names) {
        std::string kind;
        auto ends = [&](const std::string& s) {
            return path.size() > s.size() && path.compare(path.size() - s.size(), s.size(), s) == 0;
        };
        if (path == "variant.json" || path == "pass.json")
            kind = mk::files::kDescription;
        else if (ends(".330.glsl"))
            kind = mk::files::kGlsl330;
        else if (ends(".300es.glsl"))
            kind = mk::files::kEssl300;
        else if (ends(".metal"))
            kind = mk::files::kMsl;
        else if (ends(".spv"))
            kind = mk::files::kSpirv;
        else if (ends(".reflect.json"))
            kind = mk::files::kReflection;
        else if (ends(".hlsl"))
            kind = mk::files::kHlsl;
        else
            kind = mk::files::kGlsl;
        by[kind].push_back(dir + "/" + path);
    }
    for (const char* kind :
         {mk::files::kDescription, mk::files::kGlsl, mk::files::kHlsl, mk::files::kSpirv,
          mk::files::kGlsl330, mk::files::kEssl300, mk::files::kMsl, mk::files::kReflection})
        if (by.count(kind)) j[kind] = by[kind];
    return j;
}

std::string job_directory(const BuildJob& job) {
    return job.shader ? job.scene + "/" + job.shader->file_stem()
                      : variant_directory(job.scene, job.variant);
}

ManifestWriter::ManifestWriter(const Material& material, const std::vector<ManifestScene>& scenes,
                               const CausticsPasses& passes, const ReadJobFile& read,
                               WriteText write, const BindingMap* bindings)
    : material_(material), passes_(passes), read_(read), write_(std::move(write)),
      doc_(header_json(material, scenes, bindings), write_) {
    doc_.begin_array(mk::top::kVariants);
}

void ManifestWriter::add(const BuildJob& job, const JobResult& r, size_t built,
                         const BuildJob& built_job) {
    OJson v;
    v[mk::variant::kScene] = job.scene;
    v[mk::variant::kKey] = job.variant.key();
    v[mk::variant::kHash] = job.variant.short_hash();
    v[mk::variant::kContentHash] = r.content_hash;
    v[mk::variant::kNodes] = nodes_json(job.variant);
    add_fold(v, job, r);
    add_output(v, r, built, built_job, read_);
    add_passes(v, material_, job.variant, job, r, passes_);
    doc_.element(v);
}

void ManifestWriter::end() {
    doc_.end_array();
    doc_.end();
}

void write_manifest(const Material& material, const std::vector<ManifestScene>& scenes,
                    const std::vector<BuildJob>& jobs, const std::vector<JobResult>& results,
                    const CausticsPasses& passes, const ReadJobFile& read, const WriteText& write,
                    const BindingMap* bindings) {
    // Jobs are sorted by (scene, key): the manifest's order.
    ManifestWriter manifest(material, scenes, passes, read, write, bindings);
    for (size_t i = 0; i < jobs.size(); ++i)
        manifest.add(jobs[i], results[i], results[i].files_of(i), jobs[results[i].files_of(i)]);
    manifest.end();
}

namespace {

ReadJobFile read_from_results(const std::vector<JobResult>& results) {
    return [&results](size_t job, const std::string& name) -> std::optional<std::string> {
        const auto it = results[job].files.find(name);
        if (it == results[job].files.end()) return std::nullopt;
        return it->second;
    };
}

} // namespace

std::string manifest_json(const Material& material, const std::vector<ManifestScene>& scenes,
                          const std::vector<BuildJob>& jobs, const std::vector<JobResult>& results,
                          const CausticsPasses& passes, const BindingMap* bindings) {
    std::string text;
    write_manifest(
        material, scenes, jobs, results, passes, read_from_results(results),
        [&](std::string_view piece) { text += piece; }, bindings);
    return text;
}

namespace {

// Where each selector of a built shader lives: its constant id (specialized) or block offset
// (branching), from its variant.json; a selector the shader no longer reads is left out.
std::map<std::string, uint32_t> selector_places(const std::optional<std::string>& description,
                                                BuildMode mode) {
    std::map<std::string, uint32_t> places;
    if (!description) return places;
    const OJson d = OJson::parse(*description);
    if (mode == BuildMode::Specialized) {
        for (const auto& c : d.value(mk::reflection::kSpecializationConstants, OJson::array()))
            if (c[mk::member::kConstantIds].size() == 1)
                places[c[mk::member::kName]] = c[mk::member::kConstantIds][0];
    } else {
        for (const auto& m :
             d[mk::reflection::kUniformBlock].value(mk::uniform_block::kMembers, OJson::array()))
            places[m[mk::member::kName]] = m[mk::member::kOffset];
    }
    return places;
}

using Places = std::map<std::string, uint32_t>;

bool has_file(const JobResult& r, const std::string& name) {
    return std::binary_search(r.file_names().begin(), r.file_names().end(), name);
}

// The shader's entry; the selector places of its built job into `places`.
OJson shader_json(size_t i, const std::vector<BuildJob>& jobs,
                  const std::vector<JobResult>& results, BuildMode mode, const ReadJobFile& read,
                  Places& places) {
    const BuildJob& job = jobs[i];
    const ShaderChoices& s = *job.shader;
    OJson v;
    v[mk::shader::kScene] = job.scene;
    v[mk::shader::kKey] = s.key();
    v[mk::shader::kContentHash] = results[i].content_hash;
    OJson choices = OJson::object();
    for (const auto& a : axes())
        choices[a.name] = s.offered(a.name);
    v[mk::shader::kAxes] = choices;
    const size_t built = results[i].files_of(i);
    add_output(v, results[i], built, jobs[built], read);
    places = selector_places(read(built, "variant.json"), mode);
    OJson selectors = OJson::array();
    for (const auto& axis : s.switched_axes()) {
        OJson sel = {{mk::selector::kAxis, axis},
                     {mk::selector::kParameter, selector_parameter(axis)},
                     {mk::selector::kChoices, s.offered(axis)}};
        if (const auto p = places.find(selector_parameter(axis)); p != places.end())
            sel[mode == BuildMode::Specialized ? mk::selector::kConstantId
                                               : mk::selector::kOffset] = p->second;
        selectors.push_back(sel);
    }
    v[mk::shader::kSelectors] = selectors;
    v[mk::shader::kVariants] = job.serves->size();
    add_fold(v, job, results[i]);
    return v;
}

// A variant as the shader of its job draws it: the selector values, where they go, and (with
// freeze) the variant's own frozen SPIR-V.
OJson served_json(const Material& material, const Variant& variant, size_t i,
                  const std::vector<BuildJob>& jobs, const std::vector<JobResult>& results,
                  BuildMode mode, bool freeze, const CausticsPasses& passes, const Places& places) {
    const BuildJob& job = jobs[i];
    const size_t built = results[i].files_of(i);
    OJson v;
    v[mk::variant::kScene] = job.scene;
    v[mk::variant::kKey] = variant.key();
    v[mk::variant::kHash] = variant.short_hash();
    v[mk::variant::kShader] = job_directory(jobs[built]);
    v[mk::variant::kNodes] = nodes_json(variant);
    OJson values = OJson::object(), placed = OJson::array();
    for (const auto& [name, value] : job.shader->selector_values(variant)) {
        values[name] = value;
        if (const auto p = places.find(name); p != places.end())
            placed.push_back(mode == BuildMode::Specialized
                                 ? OJson{{mk::placed::kId, p->second},
                                         {mk::placed::kName, name},
                                         {mk::placed::kValue, value}}
                                 : OJson{{mk::placed::kName, name},
                                         {mk::placed::kOffset, p->second},
                                         {mk::placed::kValue, value}});
    }
    v[mk::variant::kSelectors] = values;
    v[mode == BuildMode::Specialized ? mk::variant::kSpecializationConstants
                                     : mk::variant::kUniforms] = placed;
    if (freeze && mode == BuildMode::Specialized) {
        OJson frozen = OJson::object();
        for (const char* lang : {"glsl", "hlsl"})
            if (has_file(results[built], std::string(lang) + "/water.frag.opt.spv"))
                frozen[lang] = job_directory(jobs[built]) + "/" + frozen_path(lang, variant);
        v[mk::variant::kFrozen] = frozen;
    }
    add_passes(v, material, variant, job, results[i], passes);
    return v;
}

} // namespace

void write_modes_manifest(const Material& material, BuildMode mode, bool freeze,
                          const std::vector<ManifestScene>& scenes,
                          const std::vector<BuildJob>& jobs, const std::vector<JobResult>& results,
                          const CausticsPasses& passes, const ReadJobFile& read,
                          const WriteText& write, const BindingMap* bindings) {
    OJson head = header_json(material, scenes, bindings);
    head[mk::top::kMode] = to_string(mode);
    JsonDocumentWriter doc(head, write);
    std::vector<Places> places(jobs.size());
    doc.begin_array(mk::top::kShaders);
    std::vector<std::tuple<std::string, std::string, size_t>> order; // (scene, key, job)
    for (size_t i = 0; i < jobs.size(); ++i)
        order.emplace_back(jobs[i].scene, job_key(jobs[i]), i);
    std::sort(order.begin(), order.end());
    std::map<std::string, std::vector<size_t>> shaders; // per scene, its shaders' jobs
    for (const auto& [scene, key, i] : order) {
        if (!jobs[i].shader) continue;
        doc.element(shader_json(i, jobs, results, mode, read, places[i]));
        shaders[scene].push_back(i);
    }
    doc.end_array();
    // Each variant once, sorted by (scene, key): per scene, its shaders' lists (each sorted by
    // key) merged one variant at a time.
    doc.begin_array(mk::top::kVariants);
    struct Next {
        std::string key;
        size_t job, k;
        Variant variant;
        bool operator>(const Next& o) const { return std::tie(key, job) > std::tie(o.key, o.job); }
    };
    for (const auto& [scene, served_by] : shaders) {
        std::priority_queue<Next, std::vector<Next>, std::greater<>> next;
        auto push = [&](size_t i, size_t k) {
            if (k == jobs[i].serves->size()) return;
            Variant v = jobs[i].serves->at(k);
            std::string key = v.key();
            next.push({std::move(key), i, k, std::move(v)});
        };
        for (size_t i : served_by)
            push(i, 0);
        while (!next.empty()) {
            const Next n = next.top();
            next.pop();
            doc.element(served_json(material, n.variant, n.job, jobs, results, mode, freeze, passes,
                                    places[n.job]));
            push(n.job, n.k + 1);
        }
    }
    doc.end_array();
    doc.end();
}

std::string frozen_path(const std::string& language, const Variant& v) {
    return language + "/frozen/" + v.file_stem() + ".frag.spv";
}

FrozenVariant freeze_variant(const std::string& module, const std::string& description,
                             const ShaderChoices& shader, const Variant& v,
                             const std::string& language, const BuildCache& cache) {
    FrozenVariant out;
    const Places places = selector_places(description, BuildMode::Specialized);
    std::map<uint32_t, float> values;
    for (const auto& [parameter, value] : shader.selector_values(v))
        if (const auto p = places.find(parameter); p != places.end())
            values[p->second] = static_cast<float>(value);

    // The frozen module follows from the module and the constants' values (exact, as hex
    // floats) under one toolchain: the same key finds the same bytes, verified on the way out.
    std::string constants = "frozen";
    for (const auto& [id, value] : values)
        constants += fmt::format("|{}={:a}", id, value);
    out.content_hash = content_hash({constants, module});
    CacheUse use =
        cache.load_or_make(out.content_hash, {kFrozenCacheFile}, [&]() -> std::optional<FileMap> {
            std::vector<uint32_t> words(module.size() / sizeof(uint32_t));
            std::memcpy(words.data(), module.data(), words.size() * sizeof(uint32_t));
            OptimizeResult frozen = freeze_specialization(words, values, frozen_path(language, v));
            out.diagnostics = std::move(frozen.diagnostics);
            if (frozen.spirv.empty()) return std::nullopt;
            return FileMap{
                {kFrozenCacheFile, std::string(reinterpret_cast<const char*>(frozen.spirv.data()),
                                               frozen.spirv.size() * sizeof(uint32_t))}};
        });
    out.cached = use.cached;
    out.cache_rejected = std::move(use.rejected);
    if (use.files) out.spirv = std::move(use.files->at(kFrozenCacheFile));
    return out;
}

} // namespace watergen
