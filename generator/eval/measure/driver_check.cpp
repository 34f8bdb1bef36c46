#include "watergen/eval/measure/driver_check.h"

#include <set>
#include <thread>

#include "watergen/runtime/pass_pipeline.h"
#include "watergen/runtime/shader_build.h"

namespace watergen {

namespace {

// The pipeline of one language path of `v` (a variant or a pass's shader) as the build lists it.
std::optional<AcoPipelineSource> source_of(const ShaderBuild& build, const BuildVariant& v,
                                           const std::string& lang, const std::string& name,
                                           std::string* error) {
    AcoPipelineSource s;
    s.name = name;
    auto vs = build.spirv(v, lang, ShaderStage::Vertex, error);
    auto fs = vs ? build.spirv(v, lang, ShaderStage::Fragment, error) : std::nullopt;
    auto vr = fs ? build.reflection(v, lang, ShaderStage::Vertex, error) : std::nullopt;
    auto fr = vr ? build.reflection(v, lang, ShaderStage::Fragment, error) : std::nullopt;
    if (!fr) return std::nullopt;
    s.vertex = std::move(*vs);
    s.fragment = std::move(*fs);
    s.vertex_reflection = std::move(*vr);
    s.fragment_reflection = std::move(*fr);
    for (const auto& [id, value] : v.specialization)
        s.specialization[id] = static_cast<float>(value);
    return s;
}

// Whether the build wrote `lang`'s SPIR-V for `v` (a scene's targets may leave a language out).
bool has_language(const BuildVariant& v, const std::string& lang) {
    const auto it = v.files.find("spirv");
    if (it == v.files.end()) return false;
    for (const std::string& f : it->second)
        if (f.rfind(lang + "/", 0) == 0 || f.find("/" + lang + "/") != std::string::npos)
            return true;
    return false;
}

} // namespace

DriverCheck check_build_on_drivers(const std::filesystem::path& build_dir,
                                   const std::vector<GpuTarget>& targets,
                                   const std::filesystem::path& scratch,
                                   const std::filesystem::path& worker) {
    DriverCheck out;
    // A check names only what it compiled: lavapipe, or no family at all, is refused rather
    // than reported as checked.
    if (has_lavapipe(targets) || targets.empty()) {
        out.error = "the driver check compiles on AMD families only (" + amd_target_names() +
                    "); got " + (targets.empty() ? std::string("none") : std::string("lavapipe"));
        return out;
    }
    const auto build = ShaderBuild::open(build_dir, &out.error);
    if (!build) return out;
    std::vector<AcoPipelineSource> sources;
    std::set<std::string> passes_seen; // a pass many variants share is compiled once
    for (const BuildVariant& v : build->variants())
        for (const char* lang : {"glsl", "hlsl"}) {
            if (!has_language(v, lang)) continue;
            const std::string name = (v.scene.empty() ? "" : v.scene + "/") + v.key + " " + lang;
            auto s = source_of(*build, v, lang, name, &out.error);
            if (!s) return out;
            sources.push_back(std::move(*s));
            for (const auto& [pass_name, ref] : v.passes) {
                if (!passes_seen.insert(ref.directory + " " + lang).second) continue;
                const auto pass = build->pass(v, pass_name, &out.error);
                if (!pass) return out;
                auto p = source_of(*build, pass->shader, lang, "pass " + ref.directory + " " + lang,
                                   &out.error);
                if (!p) return out;
                const auto geometry = pass_geometry(ref.draw, p->vertex_reflection, &out.error);
                const auto format = geometry ? pass_format(ref.draw, &out.error) : std::nullopt;
                if (!format) return out;
                p->geometry = *geometry;
                p->format = *format;
                sources.push_back(std::move(*p));
            }
        }
    out.pipelines = sources.size();
    const auto runs = compile_on_targets(targets, sources, scratch,
                                         std::max(1u, std::thread::hardware_concurrency()), worker);
    for (const auto& run : runs) {
        if (!run.ok()) {
            out.failures.push_back(run.error);
            out.no_device = out.no_device || run.no_device;
            continue;
        }
        for (const auto& p : run.pipelines)
            if (!p.ok()) out.failures.push_back(run.target.name + ": " + p.name + ": " + p.error);
    }
    return out;
}

} // namespace watergen
