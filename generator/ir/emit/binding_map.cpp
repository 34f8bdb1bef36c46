#include "watergen/ir/emit/binding_map.h"
#include "watergen/ir/core/diagnostic.h"

#include <algorithm>
#include <map>
#include <tuple>

namespace watergen {

const char* to_string(ResourceKind kind) {
    switch (kind) {
    case ResourceKind::UniformBlock:
        return "uniform_block";
    case ResourceKind::Sampler:
        return "sampler";
    case ResourceKind::Texture:
        return "texture";
    case ResourceKind::PushConstant:
        return "push_constant";
    }
    return "texture";
}

std::optional<ResourceKind> parse_resource_kind(const std::string& word) {
    for (ResourceKind k : {ResourceKind::UniformBlock, ResourceKind::Sampler, ResourceKind::Texture,
                           ResourceKind::PushConstant})
        if (word == to_string(k)) return k;
    return std::nullopt;
}

ResourceKind default_resource_kind(const std::string& name) {
    if (name == kParamsResource) return ResourceKind::UniformBlock;
    if (name == kSamplerResource) return ResourceKind::Sampler;
    return ResourceKind::Texture;
}

const ResourceSlot* BindingMap::find(const std::string& resource) const {
    const auto it = std::find_if(slots.begin(), slots.end(),
                                 [&](const ResourceSlot& s) { return s.name == resource; });
    return it == slots.end() ? nullptr : &*it;
}

const ResourceSlot* BindingMap::push_constant() const {
    const auto it = std::find_if(slots.begin(), slots.end(), [](const ResourceSlot& s) {
        return s.kind == ResourceKind::PushConstant;
    });
    return it == slots.end() ? nullptr : &*it;
}

namespace {

// HLSL registers, Metal indices and GL units are counted per class: a uniform block and a
// texture may both be index 0. (GL counts samplers with textures: a unit holds both.) A push
// constant is a buffer to Metal and a uniform block to GL, as SPIRV-Cross writes it there.
bool is_block(ResourceKind k) {
    return k == ResourceKind::UniformBlock || k == ResourceKind::PushConstant;
}
char hlsl_class(ResourceKind k) {
    return is_block(k) ? 'b' : k == ResourceKind::Sampler ? 's' : 't';
}
const char* msl_class(ResourceKind k) {
    return is_block(k) ? "buffer" : k == ResourceKind::Sampler ? "sampler" : "texture";
}
const char* gl_class(ResourceKind k) {
    return is_block(k) ? "uniform block binding" : "texture unit";
}

std::string where(const ResourceSlot& s) {
    return "'" + s.name + "'" + (s.origin.empty() ? "" : " (" + s.origin + ")");
}

} // namespace

std::optional<BindingConflict> BindingMap::conflict() const {
    using Place = std::tuple<int, std::string, uint32_t, uint32_t>; // target, class, index, space
    std::map<Place, const ResourceSlot*> taken;
    std::map<std::string, const ResourceSlot*> names;
    const ResourceSlot* push = nullptr;
    for (size_t i = 0; i < slots.size(); ++i) {
        const ResourceSlot& s = slots[i];
        if (auto [it, fresh] = names.emplace(s.name, &s); !fresh)
            return BindingConflict{"resource " + where(*it->second) +
                                       " is mapped twice, again at " +
                                       (s.origin.empty() ? std::string("a later entry") : s.origin),
                                   i};
        const bool pushed = s.kind == ResourceKind::PushConstant;
        if (pushed && push)
            return BindingConflict{"resources " + where(*push) + " and " + where(s) +
                                       " are both push constants; expected one (a pipeline "
                                       "has one push-constant range)",
                                   i};
        if (pushed) push = &s;
        // The sampler and the textures share GL texture units only in that a unit holds one of
        // each; a separate sampler never takes a unit in GLSL 330 (SPIRV-Cross combines it into
        // each texture), so it is not counted there.
        std::vector<std::pair<Place, std::string>> places;
        if (!pushed) { // a push constant has no descriptor and no register
            places.push_back(
                {{0, "", s.set, s.binding},
                 "Vulkan set " + std::to_string(s.set) + " binding " + std::to_string(s.binding)});
            places.push_back(
                {{1, std::string(1, hlsl_class(s.kind)), s.hlsl_register, s.hlsl_space},
                 "HLSL register(" + std::string(1, hlsl_class(s.kind)) +
                     std::to_string(s.hlsl_register) + ", space" + std::to_string(s.hlsl_space) +
                     ")"});
        }
        places.push_back({{2, msl_class(s.kind), s.msl_index, 0},
                          std::string("Metal [[") + msl_class(s.kind) + "(" +
                              std::to_string(s.msl_index) + ")]]"});
        if (s.kind != ResourceKind::Sampler)
            places.push_back(
                {{3, gl_class(s.kind), s.gl_unit, 0},
                 std::string("GL ") + gl_class(s.kind) + " " + std::to_string(s.gl_unit)});
        for (const auto& [place, text] : places)
            if (auto [it, fresh] = taken.emplace(place, &s); !fresh)
                return BindingConflict{"resources " + where(*it->second) + " and " + where(s) +
                                           " are both at " + text +
                                           "; expected one resource per slot",
                                       i};
    }
    return std::nullopt;
}

bool only_binding_map_errors(const std::vector<Diagnostic>& diagnostics, const BindingMap* map) {
    bool any = false;
    for (const Diagnostic& d : diagnostics) {
        if (d.severity != Severity::Error) continue;
        if (!map || d.file != map->name) return false;
        any = true;
    }
    return any;
}

} // namespace watergen
