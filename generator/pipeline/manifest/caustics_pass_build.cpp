#include "watergen/pipeline/manifest/caustics_pass_build.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "watergen/pipeline/manifest/manifest.h"

#include "watergen/runtime/manifest_schema.h"
#include "watergen/water/nodes/caustics.h"

namespace watergen {

namespace {

using OJson = nlohmann::ordered_json;
namespace mk = manifest_schema;

constexpr const char* kStem = "caustics";

std::string pass_key(const CausticsPassKey& key) {
    return std::string("caustics.") + to_string(key.method) + "." + key.wave_model;
}

// The pass's vertex graph with the material's values, as compose() gives the water shader its.
Graph settled(const Material& material, Graph g) {
    for (const auto& name : material.settle_parameters(g))
        g.error("preset '" + material.preset + "': parameter '" + name + "' has another size");
    return g;
}

OJson pass_json(const CausticsPassBuild& b, const CausticsPassKey& key) {
    OJson j;
    j["generator"] = stamp_text(pass_key(key));
    j["key"] = pass_key(key);
    j["method"] = to_string(key.method);
    j["wave_model"] = key.wave_model;
    j["vertex_input"] = OJson::array({{{"name", "grid_xz"}, {"location", 0}, {"type", "vec2"}}});
    // The fragment stage reads no parameter: the one block is the vertex stage's.
    const ShaderInterface& in = b.languages[0].vertex.source.interface;
    j["uniform_block"] = uniform_block_json(in);
    if (!in.specialization.empty()) j["specialization_constants"] = specialization_json(in);
    OJson counts = OJson::object();
    for (const auto& lang : b.languages)
        counts[to_string(lang.language)] = {
            {"vertex", lang.vertex.toolchain.instruction_count},
            {"vertex_optimized", lang.vertex.toolchain.instruction_count_optimized},
            {"fragment", lang.fragment.toolchain.instruction_count}};
    j["spirv_instructions"] = counts;
    return j;
}

// What the engine draws: the grid over the window grown by caustics_margin(), additively into a
// cleared single-channel float target. The grid densities are `watergen caustics`'s (photons
// need more per texel: each lands whole in one texel).
OJson draw_json(CausticsMethod method, uint32_t texels) {
    const bool photons = method == CausticsMethod::PhotonSplat;
    OJson d = {{mk::draw::kPrimitive, photons ? "points" : "triangles"},
               {mk::draw::kAttribute, "grid_xz"},
               {mk::draw::kCellsPerTexel, photons ? 8 : 2},
               {mk::draw::kMargin,
                {{mk::margin::kParameter, "caustics_depth"},
                 {mk::margin::kScale, kCausticsMarginPerDepth},
                 {mk::margin::kAdd, kCausticsMarginAdd}}},
               {mk::draw::kWindow, "caustics_window"},
               {mk::draw::kTexels, texels},
               {mk::draw::kFormat, "R32_SFLOAT"},
               {mk::draw::kChannel, "r"},
               {mk::draw::kClear, 0.0},
               {mk::draw::kBlend, "additive"}};
    if (photons) d[mk::draw::kPhotonShare] = "caustics_photon_share";
    return d;
}

// caustics_map_texels as the variant has it: folded by its scene, set by the material, or the
// node's default.
uint32_t map_texels(const Material& material,
                    const std::map<std::string, std::vector<double>>& folded) {
    const Parameter p = caustics_map_texels();
    double texels = p.default_value[0];
    if (const auto s = material.parameters.find(p.name);
        s != material.parameters.end() && s->second.value)
        texels = s->second.value->at(0);
    if (const auto f = folded.find(p.name); f != folded.end() && !f->second.empty())
        texels = f->second[0];
    return static_cast<uint32_t>(std::lround(texels));
}

} // namespace

std::optional<CausticsPassKey> caustics_pass_for(const Variant& v) {
    const auto method = caustics_pass_method(v.choice("caustics"));
    if (!method) return std::nullopt;
    return CausticsPassKey{*method, v.choice("waves")};
}

std::string caustics_pass_directory(const CausticsPassKey& key) {
    return std::string(kPassesDirectory) + "/caustics-" + to_string(key.method) + "-" +
           key.wave_model;
}

CausticsPassBuild build_caustics_pass_files(const Material& material, const CausticsPassKey& key,
                                            const BuildCache& cache, const BindingMap* bindings) {
    CausticsPassBuild b;
    b.pass = build_caustics_pass(key.method, key.wave_model);
    b.pass.vertex = settled(material, std::move(b.pass.vertex));
    b.languages = emit_two_stages(b.pass.vertex, b.pass.fragment, caustics_skeleton(key.method),
                                  kStem, pass_key(key), b.diagnostics, bindings);
    if (!b.ok()) return b;
    // The files follow from the sources and the interface (pass.json's uniform block, with
    // defaults and ranges the sources do not spell out) under one toolchain, as a variant's do.
    std::vector<std::string> parts{pass_key(key)};
    for (const auto& lang : b.languages)
        for (const StageBuild* s : {&lang.vertex, &lang.fragment}) {
            parts.push_back(s->source.source);
            parts.push_back(slots_text(s->source.interface));
        }
    const ShaderInterface& in = b.languages[0].vertex.source.interface;
    parts.push_back(uniform_block_json(in).dump());
    parts.push_back(specialization_json(in).dump());
    b.content_hash = content_hash(parts);
    std::vector<std::string> expected = stage_file_list(kStem);
    expected.push_back("pass.json");
    std::sort(expected.begin(), expected.end());
    CacheUse use = cache.load_or_make(b.content_hash, expected, [&]() -> std::optional<FileMap> {
        compile_two_stages(b.languages, b.diagnostics, StageCompile{false, nullptr});
        if (!b.ok()) return std::nullopt;
        FileMap files;
        add_stage_files(b.languages, kStem, pass_key(key), files);
        files["pass.json"] = pass_json(b, key).dump(2) + "\n";
        return files;
    });
    b.cached = use.cached;
    b.cache_rejected = std::move(use.rejected);
    if (use.files) b.files = std::move(*use.files);
    return b;
}

PassesOutput build_needed_passes(const Material& material, const JobList& jobs,
                                 const BuildOptions& options) {
    std::map<CausticsPassKey, std::set<Target>> wanted; // pass -> the targets of its variants
    for (size_t i = 0; i < jobs.size(); ++i) {
        const BuildJob job = jobs.at(i);
        auto want = [&](const Variant& v) {
            if (const auto key = caustics_pass_for(v))
                wanted[*key].insert(job.targets.begin(), job.targets.end());
        };
        if (!job.shader) want(job.variant);
        Variant v = default_variant();
        for (size_t k = 0; job.shader && k < job.serves->size(); ++k) {
            job.serves->fill(k, v);
            want(v);
        }
    }
    std::map<CausticsPassKey, std::vector<Target>> needed; // in all_targets() order
    std::vector<CausticsPassKey> keys;
    for (const auto& [key, targets] : wanted) {
        needed[key].assign(targets.begin(), targets.end());
        keys.push_back(key);
    }
    std::vector<CausticsPassBuild> built(keys.size());
    parallel_for(keys.size(), options.threads, [&](size_t k) {
        built[k] = build_caustics_pass_files(material, keys[k], options.cache, options.bindings);
    });
    PassesOutput out;
    for (size_t k = 0; k < keys.size(); ++k) {
        const std::string dir = caustics_pass_directory(keys[k]);
        if (!built[k].cache_rejected.empty())
            out.cache_rejected.push_back(
                options.cache.rejected_warning(built[k].content_hash, built[k].cache_rejected));
        out.cached += built[k].cached ? 1 : 0;
        if (!built[k].ok()) {
            ++out.failed;
            if (only_binding_map_errors(built[k].diagnostics, options.bindings))
                ++out.failed_by_map;
            out.diagnostics.insert(out.diagnostics.end(), built[k].diagnostics.begin(),
                                   built[k].diagnostics.end());
            out.diagnostics.push_back({Severity::Error, "", 0, 0, "", dir + " failed to build"});
        }
        for (const auto& [path, bytes] : filter_targets(built[k].files, needed[keys[k]]))
            out.files[dir + "/" + path] = bytes;
        out.passes.emplace(keys[k], std::move(built[k]));
    }
    return out;
}

OJson passes_entry(const Material& material, const Variant& v, const std::vector<Target>& targets,
                   const std::map<std::string, std::vector<double>>& folded,
                   const CausticsPasses& passes) {
    const auto key = caustics_pass_for(v);
    if (!key) return nullptr;
    const auto it = passes.find(*key);
    if (it == passes.end() || !it->second.ok()) return nullptr;
    const std::string dir = caustics_pass_directory(*key);
    OJson values = OJson::object();
    for (const Parameter& p : it->second.languages[0].vertex.source.interface.parameters)
        if (const auto f = folded.find(p.name); f != folded.end()) values[p.name] = f->second;
    OJson c;
    c[mk::pass::kMethod] = to_string(key->method);
    c[mk::pass::kWaveModel] = key->wave_model;
    c[mk::pass::kDirectory] = dir;
    c[mk::pass::kFiles] = files_json(dir, filter_targets(it->second.files, targets));
    c[mk::pass::kDraw] = draw_json(key->method, map_texels(material, folded));
    c[mk::pass::kValues] = values;
    return {{mk::passes::kCaustics, c}};
}

} // namespace watergen
