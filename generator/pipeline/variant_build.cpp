#include "watergen/pipeline/variant_build.h"

#include <algorithm>
#include <optional>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "watergen/ir/vertex_emitter.h"
#include "watergen/runtime/reflection.h"
#include "watergen/toolchain/spirv_tools_stage.h"
#include "watergen/water/binding_profiles.h"

namespace watergen {

namespace {

const char* kStem = "water";

// The names of the files one stage of one language writes (variant_files fills them).
struct StageFileNames {
    std::string source, spirv, spirv_optimized, glsl330, essl300, msl, reflection;
};

StageFileNames stage_file_names(Language lang, ShaderStage stage, const std::string& stem = kStem) {
    const std::string dir = std::string(to_string(lang)) + "/";
    const std::string base = dir + stem + "." + (stage == ShaderStage::Vertex ? "vert" : "frag");
    return {dir + stem + "." + file_extension(lang, stage),
            base + ".spv",
            base + ".opt.spv",
            base + ".330.glsl",
            base + ".300es.glsl",
            base + ".metal",
            base + ".reflect.json"};
}

constexpr Language kLanguages[] = {Language::Glsl, Language::Hlsl};
constexpr ShaderStage kStages[] = {ShaderStage::Vertex, ShaderStage::Fragment};

} // namespace

StageBuild build_stage(EmittedShader source, Diagnostics& all, const StageCompile& compile,
                       const std::string& key, bool strict_half) {
    StageBuild stage{std::move(source), {}};
    const CompileRequest request = stage_request(stage.source, strict_half);
    const CrossCompile cross = stage_cross(stage.source.language, compile);
    stage.toolchain =
        compile.memo ? compile.memo->run(request, cross, key) : run_toolchain(request, cross);
    add_specialization_ranges(stage.toolchain.reflection, stage.source.interface.specialization);
    Diagnostics ds = stage.toolchain.diagnostics;
    if (!has_errors(ds)) {
        Diagnostics off = check_reflected_bindings(stage.toolchain.reflection, stage.source);
        ds.insert(ds.end(), off.begin(), off.end());
    }
    // Only glslang's diagnostics point at lines of our emitted source.
    Diagnostics own, rest;
    for (auto& d : ds)
        (d.file == stage.source.file_name ? own : rest).push_back(d);
    attribute_to_nodes(stage.source, own);
    all.insert(all.end(), own.begin(), own.end());
    all.insert(all.end(), rest.begin(), rest.end());
    return stage;
}

namespace {

std::string spirv_bytes(const std::vector<uint32_t>& words) {
    return std::string(reinterpret_cast<const char*>(words.data()),
                       words.size() * sizeof(uint32_t));
}

std::string with_stamp(const std::string& stamp, const std::string& text) {
    return "// " + stamp + "\n" + text;
}

// A parameter as variant.json lists it; `place` says where it lives (a block offset, or the
// ids of its specialization constants).
nlohmann::ordered_json describe_parameter(const Parameter& p, const char* place_key,
                                          const nlohmann::ordered_json& place) {
    nlohmann::ordered_json j = {{"name", p.name},   {"type", type_name(p.type)},
                                {place_key, place}, {"default", p.default_value},
                                {"min", p.min},     {"max", p.max},
                                {"unit", p.unit},   {"seed", p.seed},
                                {"node", p.origin}};
    if (p.array_size) { // elements kArrayStride bytes apart; "default" holds them all
        j["array_size"] = p.array_size;
        j["array_stride"] = kArrayStride;
    }
    return j;
}

nlohmann::ordered_json describe(const VariantBuild& b) {
    nlohmann::ordered_json j;
    j["generator"] = stamp_text(b.shader.key());
    j["key"] = b.shader.key();
    j["preset"] = b.shader.preset;
    nlohmann::ordered_json choices = nlohmann::ordered_json::object();
    for (const auto& a : axes())
        if (b.shader.switched)
            choices[a.name] = b.shader.switched->offered(a.name);
        else
            choices[a.name] = b.shader.variant.choice(a.name);
    j["choices"] = choices;
    if (b.shader.switched) j["mode"] = to_string(b.shader.switched->mode);
    const ShaderInterface& in = b.languages[0].fragment.source.interface;
    j["uniform_block"] = uniform_block_json(in);
    if (const ResourceSlot* sampler = in.slot(kSamplerResource))
        j["sampler"] = {
            {"name", sampler->name}, {"set", sampler->set}, {"binding", sampler->binding}};
    nlohmann::ordered_json textures = nlohmann::ordered_json::array();
    for (const auto& t : in.textures)
        textures.push_back({{"name", t.name},
                            {"set", t.set},
                            {"binding", t.binding},
                            {"type", type_name(t.type)}});
    j["textures"] = textures;
    // Only when there are some, so variants without them keep their form.
    if (!in.specialization.empty()) j["specialization_constants"] = specialization_json(in);
    nlohmann::ordered_json counts = nlohmann::ordered_json::object();
    for (const auto& lang : b.languages)
        counts[to_string(lang.language)] = {
            {"fragment", lang.fragment.toolchain.instruction_count},
            {"fragment_optimized", lang.fragment.toolchain.instruction_count_optimized},
            {"vertex", lang.vertex.toolchain.instruction_count}};
    j["spirv_instructions"] = counts;
    return j;
}

} // namespace

nlohmann::ordered_json uniform_block_json(const ShaderInterface& in) {
    nlohmann::ordered_json params = nlohmann::ordered_json::array();
    for (const auto& slot : in.uniforms.members)
        for (const auto& p : in.parameters)
            if (p.name == slot.name) params.push_back(describe_parameter(p, "offset", slot.offset));
    const ResourceSlot* block = in.slot(kParamsResource);
    if (block && block->kind == ResourceKind::PushConstant) // no set or binding to give
        return {{"name", kParamsResource},
                {"push_constant", true},
                {"size", in.uniforms.size},
                {"members", params}};
    return {{"name", kParamsResource},
            {"set", block ? block->set : 0},
            {"binding", block ? block->binding : kParamsBinding},
            {"size", in.uniforms.size},
            {"members", params}};
}

nlohmann::ordered_json specialization_json(const ShaderInterface& in) {
    nlohmann::ordered_json constants = nlohmann::ordered_json::array();
    for (const auto& p : in.parameters) {
        if (!p.specialization) continue;
        std::vector<uint32_t> ids;
        for (const auto& s : in.specialization)
            if (s.parameter == p.name) ids.push_back(s.id);
        constants.push_back(describe_parameter(p, "constant_ids", ids));
    }
    return constants;
}

CompileRequest stage_request(const EmittedShader& stage, bool strict_half) {
    CompileRequest request{stage.language == Language::Glsl ? SourceLanguage::Glsl
                                                            : SourceLanguage::Hlsl,
                           stage.stage, stage.source, stage.file_name, "main"};
    request.hlsl_16bit_types = strict_half;
    for (const ResourceSlot& r : stage.interface.slots)
        request.msl_bindings.push_back(
            {r.set, r.binding, r.msl_index, r.kind == ResourceKind::PushConstant});
    return request;
}

std::string slots_text(const ShaderInterface& in) {
    std::string text;
    for (const ResourceSlot& r : in.slots)
        text += fmt::format("{}|{}|{}|{}|{}|{}|{}|{};", r.name, static_cast<int>(r.kind), r.set,
                            r.binding, r.hlsl_register, r.hlsl_space, r.msl_index, r.gl_unit);
    return text;
}

Diagnostics check_reflected_bindings(const Reflection& reflection, const EmittedShader& stage) {
    Diagnostics ds;
    auto off = [&](const std::string& what) {
        ds.push_back({Severity::Error, stage.file_name, 0, 0, "",
                      "reflection of the SPIR-V: " + what + "; the binding map says otherwise"});
    };
    const bool compute = stage.stage == ShaderStage::Compute;
    const uint32_t probe_buffers = probe_set(stage.interface);
    for (const DescriptorBinding& b : reflection.bindings) {
        const ResourceSlot* slot = stage.interface.slot(b.name);
        const bool probe = compute && b.set == probe_buffers;
        if (!slot) {
            if (!probe)
                off("'" + b.name + "' is bound at set " + std::to_string(b.set) + " binding " +
                    std::to_string(b.binding) + ", a resource the shader does not declare");
            continue;
        }
        if (b.set != slot->set || b.binding != slot->binding)
            off("'" + b.name + "' is at set " + std::to_string(b.set) + " binding " +
                std::to_string(b.binding) + ", expected set " + std::to_string(slot->set) +
                " binding " + std::to_string(slot->binding) + " (" + slot->origin + ")");
    }
    for (const ResourceSlot& slot : stage.interface.slots) {
        if (slot.kind == ResourceKind::PushConstant) {
            if (!reflection.push_constant || reflection.push_constant->name != slot.name)
                off("'" + slot.name + "' is declared but is not the stage's push-constant block");
            continue;
        }
        if (std::none_of(reflection.bindings.begin(), reflection.bindings.end(),
                         [&](const DescriptorBinding& b) { return b.name == slot.name; }))
            off("'" + slot.name + "' is declared but not bound");
    }
    if (reflection.push_constant) {
        const ResourceSlot* slot = stage.interface.slot(reflection.push_constant->name);
        if (!slot || slot->kind != ResourceKind::PushConstant)
            off("'" + reflection.push_constant->name +
                "' is a push-constant block, which the binding map does not make it");
    }
    return ds;
}

EmitOptions with_bindings(EmitOptions options) {
    if (!options.bindings) options.bindings = &default_binding_map();
    return options;
}

BindingMap default_map_for(std::initializer_list<const Graph*> graphs) {
    BindingMap map = default_binding_map();
    uint32_t binding = 0, index = 0;
    for (const ResourceSlot& s : map.slots) {
        if (s.set == 0) binding = std::max(binding, s.binding + 1);
        if (s.kind == ResourceKind::Texture)
            index = std::max({index, s.hlsl_register + 1, s.msl_index + 1, s.gl_unit + 1});
    }
    for (const Graph* g : graphs)
        for (const TextureInput& t : g->textures())
            if (!map.find(t.name)) {
                map.slots.push_back({t.name, ResourceKind::Texture, 0, binding++, index, 0, index,
                                     index, "after the watergen profile"});
                ++index;
            }
    return map;
}

CrossCompile stage_cross(Language language, const StageCompile& compile) {
    return language == Language::Glsl || compile.hlsl_cross_compile ? CrossCompile::Yes
                                                                    : CrossCompile::No;
}

VariantBuild build_variant(const Variant& variant, const Preset* preset,
                           const EmitOptions& options) {
    return build_shader(build_water_shader(variant, preset), options);
}

VariantBuild build_shader(WaterShader shader, const EmitOptions& given,
                          const StageCompile& compile) {
    // A shader of nodes the profile does not know (a test's own, a user's) gets their textures
    // after it, rather than an error, when the caller gave no map.
    std::optional<BindingMap> fallback;
    EmitOptions options = given;
    if (!options.bindings)
        options.bindings = &fallback.emplace(default_map_for({&shader.fragment}));
    VariantBuild b{std::move(shader), {}, {}};
    const Diagnostics& graph_errors = b.shader.fragment.diagnostics();
    b.diagnostics.insert(b.diagnostics.end(), graph_errors.begin(), graph_errors.end());
    if (has_errors(b.diagnostics)) return b;
    const std::string key = b.shader.key();
    for (size_t i = 0; i < b.languages.size(); ++i) {
        const Language lang = kLanguages[i];
        LanguageBuild& out = b.languages[i];
        out.language = lang;
        EmittedShader frag = emit_fragment(b.shader.fragment, lang,
                                           stage_file_names(lang, ShaderStage::Fragment).source,
                                           key, b.diagnostics, options);
        if (has_errors(b.diagnostics)) return b;
        out.fragment =
            build_stage(std::move(frag), b.diagnostics, compile, key, options.strict_half);
        out.vertex = build_stage(
            emit_fullscreen_vertex(lang, stage_file_names(lang, ShaderStage::Vertex).source, key),
            b.diagnostics, compile, key);
    }
    return b;
}

std::map<std::string, std::string> variant_files(const VariantBuild& b) {
    std::map<std::string, std::string> files;
    if (!b.ok()) return files;
    add_stage_files(b.languages, kStem, b.shader.key(), files);
    files["variant.json"] = describe(b).dump(2) + "\n";
    return files;
}

void add_stage_files(const std::array<LanguageBuild, 2>& languages, const std::string& stem,
                     const std::string& key, std::map<std::string, std::string>& files) {
    const std::string stamp = stamp_text(key);
    for (const auto& lang : languages) {
        for (const StageBuild* s : {&lang.vertex, &lang.fragment}) {
            const StageFileNames names = stage_file_names(lang.language, s->source.stage, stem);
            const ToolchainOutputs& t = s->toolchain;
            files[names.source] = s->source.source;
            files[names.spirv] = spirv_bytes(t.spirv);
            files[names.spirv_optimized] = spirv_bytes(t.spirv_optimized);
            files[names.reflection] = reflection_to_json(t.reflection);
            if (lang.language != Language::Glsl) continue;
            files[names.glsl330] = with_stamp(stamp, t.glsl330);
            files[names.essl300] = with_stamp(stamp, t.essl300);
            files[names.msl] = with_stamp(stamp, t.msl);
        }
    }
}

std::vector<std::string> stage_file_list(const std::string& stem) {
    std::vector<std::string> names;
    for (Language lang : kLanguages)
        for (ShaderStage stage : kStages) {
            const StageFileNames n = stage_file_names(lang, stage, stem);
            names.insert(names.end(), {n.source, n.spirv, n.spirv_optimized, n.reflection});
            if (lang == Language::Glsl) names.insert(names.end(), {n.glsl330, n.essl300, n.msl});
        }
    std::sort(names.begin(), names.end());
    return names;
}

std::vector<std::string> variant_file_names() {
    std::vector<std::string> names = stage_file_list(kStem);
    names.push_back("variant.json");
    std::sort(names.begin(), names.end());
    return names;
}

std::array<LanguageBuild, 2> emit_two_stages(const Graph& vertex, const Graph& fragment,
                                             const std::string& stage_name, const std::string& stem,
                                             const std::string& key, Diagnostics& diagnostics,
                                             const BindingMap* bindings) {
    std::optional<BindingMap> fallback;
    if (!bindings) bindings = &fallback.emplace(default_map_for({&vertex, &fragment}));
    std::array<LanguageBuild, 2> out;
    for (const Graph* g : {&vertex, &fragment})
        diagnostics.insert(diagnostics.end(), g->diagnostics().begin(), g->diagnostics().end());
    if (has_errors(diagnostics)) return out;
    for (size_t i = 0; i < out.size(); ++i) {
        const Language lang = kLanguages[i];
        out[i].language = lang;
        out[i].vertex.source = emit_vertex(vertex, lang, stage_name,
                                           stage_file_names(lang, ShaderStage::Vertex, stem).source,
                                           key, diagnostics, bindings);
        out[i].fragment.source = emit_fragment(
            fragment, lang, stage_file_names(lang, ShaderStage::Fragment, stem).source, key,
            diagnostics, EmitOptions{false, {}, LoopUnroll::AsHinted, bindings});
        if (has_errors(diagnostics)) return out;
    }
    return out;
}

void compile_two_stages(std::array<LanguageBuild, 2>& languages, Diagnostics& diagnostics,
                        const StageCompile& compile) {
    for (LanguageBuild& lang : languages) {
        lang.vertex = build_stage(std::move(lang.vertex.source), diagnostics, compile, "");
        lang.fragment = build_stage(std::move(lang.fragment.source), diagnostics, compile, "");
    }
}

std::array<LanguageBuild, 2> build_two_stages(const Graph& vertex, const Graph& fragment,
                                              const std::string& stage_name,
                                              const std::string& stem, const std::string& key,
                                              Diagnostics& diagnostics,
                                              const BindingMap* bindings) {
    std::array<LanguageBuild, 2> out =
        emit_two_stages(vertex, fragment, stage_name, stem, key, diagnostics, bindings);
    if (!has_errors(diagnostics)) compile_two_stages(out, diagnostics);
    return out;
}

} // namespace watergen
