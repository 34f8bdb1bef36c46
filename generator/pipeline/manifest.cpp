#include "watergen/pipeline/manifest.h"

#include <set>

#include <nlohmann/json.hpp>

#include "watergen/ir/emitter.h"

namespace watergen {

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
    j["name"] = m.name;
    j["description"] = m.description;
    j["preset"] = m.preset;
    OJson ax = OJson::object();
    for (size_t i = 0; i < axes().size(); ++i)
        ax[axes()[i].name] = m.space.choices[i];
    j["axes"] = ax;
    OJson rules = OJson::array();
    const size_t builtin = builtin_rules().size();
    for (size_t i = builtin; i < m.space.rules.size(); ++i) {
        const Rule& r = m.space.rules[i];
        rules.push_back({{"if", r.axis + "=" + r.choice},
                         {r.kind == Rule::Kind::Requires ? "requires" : "excludes",
                          {{r.other_axis, r.other_choices}}},
                         {"why", r.why}});
    }
    j["rules"] = rules;
    OJson params = OJson::object();
    for (const auto& [name, s] : m.parameters) {
        OJson p = OJson::object();
        if (s.value) p["value"] = *s.value;
        if (s.min) p["min"] = *s.min;
        if (s.max) p["max"] = *s.max;
        params[name] = p;
    }
    j["parameters"] = params;
    OJson targets = OJson::array();
    for (Target t : m.targets)
        targets.push_back(to_string(t));
    j["targets"] = targets;
    return j;
}

OJson scene_json(const ManifestScene& s) {
    OJson j;
    j["name"] = s.name;
    if (!s.plan) {
        j["pruned"] = false;
        j["variants"] = s.variants;
        return j;
    }
    const SceneFacts& f = s.plan->scene;
    j["pruned"] = true;
    j["description"] = f.description;
    j["file"] = f.file;
    j["facts"] = {{"shoreline", f.shoreline},
                  {"water_depth", {f.water_depth.min, f.water_depth.max}},
                  {"camera_height", {f.camera_height.min, f.camera_height.max}},
                  {"camera_pitch", {f.camera_pitch.min, f.camera_pitch.max}},
                  {"sun_elevation", {f.sun_elevation.min, f.sun_elevation.max}},
                  {"reflection_sources", f.reflection_sources},
                  {"waves", f.waves_animated ? "animated" : "static"},
                  {"precision", f.precision},
                  {"platforms", f.platforms}};
    j["variants"] = s.plan->variants.size();
    j["skipped"] = s.plan->skipped;
    OJson fixed = OJson::object();
    for (const auto& [name, v] : s.plan->fixed)
        fixed[name] = v;
    j["fixed"] = fixed;
    OJson targets = OJson::array();
    for (Target t : s.plan->targets)
        targets.push_back(to_string(t));
    j["targets"] = targets;
    return j;
}

// Files per target, as paths relative to the output directory.
OJson files_json(const std::string& dir, const FileMap& files) {
    OJson j = OJson::object();
    std::map<std::string, std::vector<std::string>> by;
    for (const auto& [path, bytes] : files) {
        std::string kind;
        auto ends = [&](const std::string& s) {
            return path.size() > s.size() && path.compare(path.size() - s.size(), s.size(), s) == 0;
        };
        if (path == "variant.json")
            kind = "description";
        else if (ends(".330.glsl"))
            kind = "glsl330";
        else if (ends(".300es.glsl"))
            kind = "essl300";
        else if (ends(".metal"))
            kind = "msl";
        else if (ends(".spv"))
            kind = "spirv";
        else if (ends(".reflect.json"))
            kind = "reflection";
        else if (ends(".hlsl"))
            kind = "hlsl";
        else
            kind = "glsl";
        by[kind].push_back(dir + "/" + path);
    }
    for (const char* kind :
         {"description", "glsl", "hlsl", "spirv", "glsl330", "essl300", "msl", "reflection"})
        if (by.count(kind)) j[kind] = by[kind];
    return j;
}

} // namespace

std::string manifest_json(const Material& material, const std::vector<ManifestScene>& scenes,
                          const std::vector<BuildJob>& jobs,
                          const std::vector<JobResult>& results) {
    OJson doc;
    doc["generator"] = std::string("watergen ") + WATERGEN_VERSION;
    doc["material"] = material_json(material);
    doc["space"] = {{"full", count_variants(full_space())},
                    {"material", count_variants(material.space)}};
    OJson sc = OJson::array();
    for (const auto& s : scenes)
        sc.push_back(scene_json(s));
    doc["scenes"] = sc;

    std::map<std::pair<std::string, std::string>, size_t> index;
    for (size_t i = 0; i < jobs.size(); ++i)
        index[{jobs[i].scene, jobs[i].variant.key()}] = i;
    OJson variants = OJson::array();
    for (const auto& [scene_key, i] : index) {
        const BuildJob& job = jobs[i];
        const JobResult& r = results[i];
        OJson v;
        v["scene"] = job.scene;
        v["key"] = job.variant.key();
        v["hash"] = job.variant.short_hash();
        v["content_hash"] = r.content_hash;
        const std::string dir = variant_directory(job.scene, job.variant);
        OJson nodes = OJson::object();
        for (const auto& a : axes())
            nodes[a.name] = a.name + "." + job.variant.choice(a.name);
        v["nodes"] = nodes;
        OJson folded = OJson::object();
        for (const auto& [name, value] : r.fold.folded_parameters)
            folded[name] = value;
        v["folded_parameters"] = folded;
        if (r.folded) {
            OJson removed_params = OJson::array(), removed_textures = OJson::array(),
                  terms = OJson::array();
            for (const auto& p : r.fold.removed_parameters)
                removed_params.push_back(
                    {{"name", p.name}, {"because", fact_texts(job.facts, p.facts)}});
            for (const auto& t : r.fold.removed_textures)
                removed_textures.push_back(
                    {{"name", t.name}, {"because", fact_texts(job.facts, t.facts)}});
            for (const auto& t : r.fold.removed)
                if (t.named) {
                    const FactSet fs = t.event >= 0
                                           ? r.fold.events[static_cast<size_t>(t.event)].facts
                                           : FactSet{};
                    terms.push_back({{"node", t.origin},
                                     {"term", t.name},
                                     {"because", fact_texts(job.facts, fs)}});
                }
            v["removed_parameters"] = removed_params;
            v["removed_textures"] = removed_textures;
            v["removed_terms"] = terms;
            v["live_ir_nodes"] = {{"before", r.fold.live_before}, {"after", r.fold.live_after}};
        }
        if (!r.same_as.empty()) {
            // Same shader as an earlier variant of the scene: its files are that variant's.
            Variant other = job.variant;
            std::string error;
            if (auto parsed = parse_variant_key(r.same_as, &error)) other = *parsed;
            v["same_as"] = r.same_as;
            v["directory"] = variant_directory(job.scene, other);
            const auto it = index.find({job.scene, r.same_as});
            const JobResult& first = it != index.end() ? results[it->second] : r;
            v["files"] = files_json(variant_directory(job.scene, other), first.files);
        } else {
            v["directory"] = dir;
            v["files"] = files_json(dir, r.files);
        }
        const auto canonical = r.same_as.empty() ? index.end() : index.find({job.scene, r.same_as});
        const JobResult& built = canonical == index.end() ? r : results[canonical->second];
        if (auto it = built.files.find("variant.json"); it != built.files.end()) {
            const OJson d = OJson::parse(it->second);
            v["reflection"] = {
                {"uniform_block", d.value("uniform_block", OJson::object())},
                {"sampler", {{"name", "linear_clamp"}, {"set", 0}, {"binding", kSamplerBinding}}},
                {"textures", d.value("textures", OJson::array())}};
            v["spirv_instructions"] = d.value("spirv_instructions", OJson::object());
        }
        variants.push_back(v);
    }
    doc["variants"] = variants;
    return doc.dump(2) + "\n";
}

} // namespace watergen
