#include "watergen/pipeline/variant/variant_build.h"

#include <algorithm>
#include <optional>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "watergen/ir/emit/tessellation_emitter.h"
#include "watergen/ir/emit/vertex_emitter.h"
#include "watergen/runtime/manifest_schema.h"
#include "watergen/runtime/reflection.h"
#include "watergen/toolchain/spirv_tools_stage.h"
#include "watergen/water/binding_profiles.h"
#include "watergen/water/tessellated_mesh.h"

namespace watergen {

// variant.json's uniform block, sampler, textures, specialization constants, geometry and
// instruction counts go into the manifest as they are: spelled with its keys.
namespace mk = manifest_schema;

namespace {

const char* kStem = "water";

// The names of the files one stage of one language writes (variant_files fills them).
struct StageFileNames {
    std::string source, spirv, spirv_optimized, glsl330, essl300, msl, reflection;
};

StageFileNames stage_file_names(Language lang, ShaderStage stage, const std::string& stem = kStem) {
    const std::string dir = std::string(to_string(lang)) + "/";
    const std::string base = dir + stem + "." + stage_tag(stage);
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
constexpr ShaderStage kPatchStages[] = {ShaderStage::TessControl, ShaderStage::TessEvaluation};

bool is_patch_stage(ShaderStage s) {
    return s == ShaderStage::TessControl || s == ShaderStage::TessEvaluation;
}

} // namespace

std::vector<const StageBuild*> LanguageBuild::stages() const {
    if (tessellated()) return {&vertex, &control, &evaluation, &fragment};
    return {&vertex, &fragment};
}

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
    nlohmann::ordered_json j = {
        {mk::member::kName, p.name},  {mk::member::kType, type_name(p.type)},
        {place_key, place},           {mk::member::kDefault, p.default_value},
        {mk::member::kMin, p.min},    {mk::member::kMax, p.max},
        {mk::member::kUnit, p.unit},  {mk::member::kSeed, p.seed},
        {mk::member::kNode, p.origin}};
    if (p.array_size) { // elements kArrayStride bytes apart; "default" holds them all
        j[mk::member::kArraySize] = p.array_size;
        j[mk::member::kArrayStride] = kArrayStride;
    }
    if (p.host.rule != HostRule::Given)
        j[mk::member::kHost] = {{mk::host::kRule, host_rule_name(p.host.rule)},
                                {mk::host::kInputs, p.host.inputs}};
    return j;
}

// What an engine needs to draw a mesh geometry besides the block: its stages, its vertex
// layout and where its grid comes from (runtime/water_grid.h).
nlohmann::ordered_json mesh_geometry_json(const MeshStages& m) {
    nlohmann::ordered_json stages = nlohmann::ordered_json::array();
    stages.push_back("vertex");
    if (m.tessellated()) stages.insert(stages.end(), {"tess_control", "tess_evaluation"});
    stages.push_back("fragment");
    nlohmann::ordered_json inputs = nlohmann::ordered_json::array();
    uint32_t location = 0, offset = 0;
    for (const auto& [name, type] : mesh_vertex_inputs()) {
        const uint32_t floats = static_cast<uint32_t>(component_count(type));
        inputs.push_back({{mk::vertex_input::kName, name},
                          {mk::vertex_input::kLocation, location++},
                          {mk::vertex_input::kFloats, floats},
                          {mk::vertex_input::kOffset, offset}});
        offset += floats * 4;
    }
    nlohmann::ordered_json j = {
        {mk::geometry::kName, m.geometry},
        {mk::geometry::kStages, stages},
        {mk::geometry::kTopology, m.tessellated() ? "patch_list" : "triangle_list"},
        {mk::geometry::kVertexStride, offset},
        {mk::geometry::kVertexInputs, inputs},
        {mk::geometry::kGrid,
         {{mk::grid::kKind, "clipmap"},
          {mk::grid::kMadeBy, "watergen::water_grid (runtime/water_grid.h)"},
          {mk::grid::kParameters, {"grid_morph_start", "grid_morph_end"}}}},
        {mk::geometry::kFrontFace, "counter_clockwise"}};
    if (m.tessellated()) {
        j[mk::geometry::kPatchControlPoints] = 4;
        j[mk::geometry::kTessellation] = {
            {mk::tessellation::kMaxFactor, kMaxTessellationFactor},
            {mk::tessellation::kParameters, {"tess_scale", "tess_max"}}};
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
    j[mk::reflection::kUniformBlock] = uniform_block_json(in);
    if (const ResourceSlot* sampler = in.slot(kSamplerResource))
        j[mk::reflection::kSampler] = {{mk::sampler::kName, sampler->name},
                                       {mk::sampler::kSet, sampler->set},
                                       {mk::sampler::kBinding, sampler->binding}};
    nlohmann::ordered_json textures = nlohmann::ordered_json::array();
    for (const auto& t : in.textures)
        textures.push_back({{mk::texture::kName, t.name},
                            {mk::texture::kSet, t.set},
                            {mk::texture::kBinding, t.binding},
                            {mk::texture::kType, type_name(t.type)}});
    j[mk::reflection::kTextures] = textures;
    // Only when there are some, so variants without them keep their form.
    if (!in.specialization.empty())
        j[mk::reflection::kSpecializationConstants] = specialization_json(in);
    if (b.shader.mesh) j[mk::output::kGeometry] = mesh_geometry_json(*b.shader.mesh);
    nlohmann::ordered_json counts = nlohmann::ordered_json::object();
    for (const auto& lang : b.languages) {
        nlohmann::ordered_json& c = counts[to_string(lang.language)];
        c = {{mk::instructions::kFragment, lang.fragment.toolchain.instruction_count},
             {mk::instructions::kFragmentOptimized,
              lang.fragment.toolchain.instruction_count_optimized},
             {mk::instructions::kVertex, lang.vertex.toolchain.instruction_count}};
        if (lang.tessellated()) {
            c[mk::instructions::kTessControl] = lang.control.toolchain.instruction_count;
            c[mk::instructions::kTessEvaluation] = lang.evaluation.toolchain.instruction_count;
        }
    }
    j[mk::output::kSpirvInstructions] = counts;
    return j;
}

} // namespace

nlohmann::ordered_json uniform_block_json(const ShaderInterface& in) {
    nlohmann::ordered_json params = nlohmann::ordered_json::array();
    for (const auto& slot : in.uniforms.members)
        for (const auto& p : in.parameters)
            if (p.name == slot.name)
                params.push_back(describe_parameter(p, mk::member::kOffset, slot.offset));
    const ResourceSlot* block = in.slot(kParamsResource);
    if (block && block->kind == ResourceKind::PushConstant) // no set or binding to give
        return {{mk::uniform_block::kName, kParamsResource},
                {mk::uniform_block::kPushConstant, true},
                {mk::uniform_block::kSize, in.uniforms.size},
                {mk::uniform_block::kMembers, params}};
    return {{mk::uniform_block::kName, kParamsResource},
            {mk::uniform_block::kSet, block ? block->set : 0},
            {mk::uniform_block::kBinding, block ? block->binding : kParamsBinding},
            {mk::uniform_block::kSize, in.uniforms.size},
            {mk::uniform_block::kMembers, params}};
}

nlohmann::ordered_json specialization_json(const ShaderInterface& in) {
    nlohmann::ordered_json constants = nlohmann::ordered_json::array();
    for (const auto& p : in.parameters) {
        if (!p.specialization) continue;
        std::vector<uint32_t> ids;
        for (const auto& s : in.specialization)
            if (s.parameter == p.name) ids.push_back(s.id);
        constants.push_back(describe_parameter(p, mk::member::kConstantIds, ids));
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

namespace {

// Emits a mesh geometry's stages before the fragment for `out.language` into `out`, with the
// block and binding map of `options`.
void emit_mesh_stages(const MeshStages& m, const std::string& key, const EmitOptions& options,
                      LanguageBuild& out, Diagnostics& ds) {
    const Language lang = out.language;
    auto file = [&](ShaderStage stage) { return stage_file_names(lang, stage).source; };
    if (!m.tessellated()) {
        out.vertex.source = emit_vertex(m.vertex, lang, "mesh", file(ShaderStage::Vertex), key, ds,
                                        options.bindings, options.block);
        return;
    }
    const PatchStageOptions patch{options.bindings, options.block};
    out.vertex.source = emit_vertex(m.vertex, lang, "mesh_patch", file(ShaderStage::Vertex), key,
                                    ds, options.bindings, options.block);
    out.control.source =
        emit_tess_control(m.control, lang, "mesh", file(ShaderStage::TessControl), key, ds, patch);
    out.evaluation.source = emit_tess_evaluation(m.evaluation, lang, "mesh",
                                                 file(ShaderStage::TessEvaluation), key, ds, patch);
}

} // namespace

std::array<LanguageBuild, 2> emit_shader_stages(const WaterShader& shader, const EmitOptions& given,
                                                Diagnostics& ds) {
    std::array<LanguageBuild, 2> out;
    const MeshStages* mesh = shader.mesh ? &*shader.mesh : nullptr;
    std::vector<const Graph*> graphs;
    if (mesh) graphs = mesh->graphs();
    graphs.push_back(&shader.fragment);
    for (const Graph* g : graphs)
        ds.insert(ds.end(), g->diagnostics().begin(), g->diagnostics().end());
    if (has_errors(ds)) return out;
    // A mesh's stages bind one parameter block: each declares all of it.
    EmitOptions options = given;
    std::vector<Parameter> block;
    const std::vector<std::pair<std::string, Type>> inputs = mesh_fragment_inputs();
    if (mesh) {
        block = shared_block_parameters(graphs, ds);
        options.block = &block;
        options.inputs = &inputs;
    }
    const std::string key = shader.key();
    for (size_t i = 0; i < out.size() && !has_errors(ds); ++i) {
        const Language lang = kLanguages[i];
        out[i].language = lang;
        out[i].fragment.source =
            emit_fragment(shader.fragment, lang,
                          stage_file_names(lang, ShaderStage::Fragment).source, key, ds, options);
        if (mesh)
            emit_mesh_stages(*mesh, key, options, out[i], ds);
        else
            out[i].vertex.source = emit_fullscreen_vertex(
                lang, stage_file_names(lang, ShaderStage::Vertex).source, key);
    }
    return out;
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
    b.languages = emit_shader_stages(b.shader, options, b.diagnostics);
    if (has_errors(b.diagnostics)) return b;
    const std::string key = b.shader.key();
    for (LanguageBuild& out : b.languages) {
        out.fragment = build_stage(std::move(out.fragment.source), b.diagnostics, compile, key,
                                   options.strict_half);
        for (StageBuild* stage : {&out.vertex, &out.control, &out.evaluation})
            if (!stage->source.file_name.empty())
                *stage = build_stage(std::move(stage->source), b.diagnostics, compile, key);
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
        for (const StageBuild* s : lang.stages()) {
            const StageFileNames names = stage_file_names(lang.language, s->source.stage, stem);
            const ToolchainOutputs& t = s->toolchain;
            files[names.source] = s->source.source;
            files[names.spirv] = spirv_bytes(t.spirv);
            files[names.spirv_optimized] = spirv_bytes(t.spirv_optimized);
            files[names.reflection] = reflection_to_json(t.reflection);
            // No cross-compilation target takes a patch stage (the toolchain's note says why).
            if (lang.language != Language::Glsl || is_patch_stage(s->source.stage)) continue;
            files[names.glsl330] = with_stamp(stamp, t.glsl330);
            files[names.essl300] = with_stamp(stamp, t.essl300);
            files[names.msl] = with_stamp(stamp, t.msl);
        }
    }
}

std::vector<std::string> stage_file_list(const std::string& stem, bool tessellated) {
    std::vector<std::string> names;
    std::vector<ShaderStage> stages(std::begin(kStages), std::end(kStages));
    if (tessellated) stages.insert(stages.end(), std::begin(kPatchStages), std::end(kPatchStages));
    for (Language lang : kLanguages)
        for (ShaderStage stage : stages) {
            const StageFileNames n = stage_file_names(lang, stage, stem);
            names.insert(names.end(), {n.source, n.spirv, n.spirv_optimized, n.reflection});
            if (lang == Language::Glsl && !is_patch_stage(stage))
                names.insert(names.end(), {n.glsl330, n.essl300, n.msl});
        }
    std::sort(names.begin(), names.end());
    return names;
}

std::vector<std::string> variant_file_names(bool tessellated) {
    std::vector<std::string> names = stage_file_list(kStem, tessellated);
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
