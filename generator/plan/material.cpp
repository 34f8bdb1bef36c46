#include "watergen/plan/material.h"

#include "watergen/ir/core/text.h"
#include "watergen/water/presets.h"

namespace watergen {

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
    WaterShader shader = build_water_shader(choices, nullptr, search);
    const Preset* p = preset.empty() ? nullptr : find_preset(preset);
    shader.preset = p ? p->name : "";
    if (has_errors(shader.fragment.diagnostics())) return shader;
    std::vector<Graph*> graphs = {&shader.fragment};
    if (shader.mesh)
        for (Graph* stage : shader.mesh->graphs())
            graphs.push_back(stage);
    for (Graph* g : graphs)
        for (const std::string& name : settle_parameters(*g))
            shader.fragment.error("preset '" + preset + "': parameter '" + name +
                                  "' has another size");
    return shader;
}

std::vector<std::string> Material::settle_parameters(Graph& g) const {
    std::vector<std::string> mismatched;
    if (const Preset* p = preset.empty() ? nullptr : find_preset(preset))
        mismatched = apply_preset(g, *p);
    for (const auto& [name, setting] : parameters) {
        const Parameter* declared = g.find_parameter(name);
        if (!declared) continue;
        if (setting.value) g.set_parameter_default(name, *setting.value);
        if (setting.min || setting.max)
            g.set_parameter_range(name, setting.min.value_or(declared->min),
                                  setting.max.value_or(declared->max));
    }
    return mismatched;
}

Material preset_material(const Preset* preset) {
    Material m;
    if (preset) m.preset = preset->name;
    return m;
}

} // namespace watergen
