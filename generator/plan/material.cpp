#include "watergen/plan/material.h"

#include "watergen/ir/text.h"
#include "watergen/water/presets.h"

namespace watergen {

namespace {

// A copy of `g` whose parameter declarations carry `params` (same nodes, same ids).
Graph with_parameters(const Graph& g, const std::vector<Parameter>& params) {
    Graph out;
    for (const Parameter& p : params)
        out.declare_parameter(p);
    for (const auto& t : g.textures())
        out.declare_texture(t);
    for (uint32_t id = 0; id < g.size(); ++id)
        out.add(g.node(id));
    for (const auto& o : g.outputs())
        out.set_output(o.name, o.node);
    for (const auto& b : g.bindings())
        out.bind(b.quantity, b.node); // same ids: the scene facts still apply
    return out;
}

} // namespace

const std::vector<Target>& all_targets() {
    static const std::vector<Target> list = {Target::Glsl,      Target::Hlsl,    Target::Spirv,
                                             Target::Glsl330,   Target::Essl300, Target::Msl,
                                             Target::Reflection};
    return list;
}

const char* to_string(Target t) {
    switch (t) {
    case Target::Glsl:
        return "glsl";
    case Target::Hlsl:
        return "hlsl";
    case Target::Spirv:
        return "spirv";
    case Target::Glsl330:
        return "glsl330";
    case Target::Essl300:
        return "essl300";
    case Target::Msl:
        return "msl";
    case Target::Reflection:
        return "reflection";
    }
    return "?";
}

std::optional<Target> parse_target(const std::string& name) {
    for (Target t : all_targets())
        if (name == to_string(t)) return t;
    return std::nullopt;
}

std::string target_names() {
    std::vector<std::string> names;
    for (Target t : all_targets())
        names.push_back(to_string(t));
    return join(names);
}

std::string SourceRef::where() const {
    if (!source) return "";
    return source->where(pointer) + " " + (pointer.empty() ? "/" : pointer);
}

Diagnostic SourceRef::error(const std::string& what) const {
    if (source) return source->error(pointer, what);
    return Diagnostic{Severity::Error, "", 0, 0, "", what};
}

// ---------------------------------------------------------------------------------------
// Material

std::pair<double, double> Material::range(const std::string& parameter) const {
    double lo = 0.0, hi = 0.0;
    if (auto it = declared.find(parameter); it != declared.end()) {
        lo = it->second.min;
        hi = it->second.max;
    }
    if (auto it = parameters.find(parameter); it != parameters.end()) {
        if (it->second.min) lo = *it->second.min;
        if (it->second.max) hi = *it->second.max;
    }
    return {lo, hi};
}

WaterShader Material::compose(const Variant& v, SurfaceSearch search) const {
    return compose(ShaderChoices::of(v), search);
}

WaterShader Material::compose(const ShaderChoices& choices, SurfaceSearch search) const {
    WaterShader shader =
        build_water_shader(choices, preset.empty() ? nullptr : find_preset(preset), search);
    if (has_errors(shader.fragment.diagnostics())) return shader;
    shader.fragment = with_settings(shader.fragment);
    return shader;
}

Graph Material::with_settings(const Graph& g) const {
    std::vector<Parameter> params = g.parameters();
    for (Parameter& p : params) {
        auto it = parameters.find(p.name);
        if (it == parameters.end()) continue;
        if (it->second.value) p.default_value = *it->second.value;
        if (it->second.min) p.min = *it->second.min;
        if (it->second.max) p.max = *it->second.max;
    }
    return with_parameters(g, params);
}

Material preset_material(const Preset* preset) {
    Material m;
    if (preset) m.preset = preset->name;
    return m;
}

} // namespace watergen
