#include "watergen/water/binding_profiles.h"

#include <map>

namespace watergen {
namespace {

// The textures watergen's nodes read: what the renderer draws each view, then the material's
// assets. A node that adds a texture adds it here, or the profiles refuse the shaders that
// read it (a test composes every choice against every profile).
const std::vector<std::string> kViewTextures = {"scene_color",    "scene_position", "sky_cube",
                                                "reflection_map", "caustics_map",   "scene_depth"};
const std::vector<std::string> kMaterialTextures = {"height_map",     "detail_normal_map",
                                                    "foam_pattern",   "fourier_coefs1",
                                                    "fourier_coefs2", "caustics_tile"};
// The watergen profile numbers textures in the order they joined, so a binding an engine
// already uses never moves: scene_depth (the depth-buffer scene input) came last.
const std::vector<std::string> kJoinedTextures = {
    "scene_color",    "scene_position", "sky_cube",          "reflection_map",
    "caustics_map",   "height_map",     "detail_normal_map", "foam_pattern",
    "fourier_coefs1", "fourier_coefs2", "caustics_tile",     "scene_depth"};

// Appends `name` at (set, binding), with its HLSL register, Metal index and GL unit counted per
// class in the order slots are added.
struct Builder {
    BindingMap map;
    std::map<ResourceKind, uint32_t> next; // per class: Metal index and GL unit
    void add(const std::string& name, uint32_t set, uint32_t binding, uint32_t reg,
             uint32_t space) {
        const ResourceKind kind = default_resource_kind(name);
        const uint32_t index = next[kind]++;
        map.slots.push_back(
            {name, kind, set, binding, reg, space, index, index, "profile " + map.name});
    }
};

BindingMap watergen_profile() {
    Builder b{{"watergen", {}}, {}};
    b.add(kParamsResource, 0, 0, 0, 0);
    b.add(kSamplerResource, 0, 1, 0, 0);
    uint32_t t = 0;
    for (const std::string& name : kJoinedTextures) {
        b.add(name, 0, 2 + t, t, 0);
        ++t;
    }
    return b.map;
}

BindingMap frequency_sets_profile() {
    Builder b{{"frequency_sets", {}}, {}};
    uint32_t t = 0;
    for (const std::string& name : kViewTextures)
        b.add(name, 0, t, t, 0), ++t;
    b.add(kParamsResource, 2, 0, 0, 2);
    b.add(kSamplerResource, 2, 1, 0, 2);
    uint32_t m = 0;
    for (const std::string& name : kMaterialTextures)
        b.add(name, 2, 2 + m, m, 2), ++m;
    return b.map;
}

// DXC's register shifts: a class's register r in space s is Vulkan set s, binding r + shift.
constexpr uint32_t kTextureShift = 16, kSamplerShift = 32;

BindingMap register_spaces_profile() {
    Builder b{{"register_spaces", {}}, {}};
    b.add(kParamsResource, 0, 0, 0, 0);
    b.add(kSamplerResource, 0, kSamplerShift, 0, 0);
    uint32_t space = 1;
    for (const auto* list : {&kViewTextures, &kMaterialTextures}) {
        uint32_t t = 0;
        for (const std::string& name : *list)
            b.add(name, space, kTextureShift + t, t, space), ++t;
        ++space;
    }
    return b.map;
}

const std::map<std::string, BindingMap>& profiles() {
    static const std::map<std::string, BindingMap> all = {
        {"watergen", watergen_profile()},
        {"frequency_sets", frequency_sets_profile()},
        {"register_spaces", register_spaces_profile()}};
    return all;
}

} // namespace

const BindingMap* binding_profile(const std::string& name) {
    const auto it = profiles().find(name);
    return it == profiles().end() ? nullptr : &it->second;
}

const std::vector<std::string>& binding_profile_names() {
    static const std::vector<std::string> names = {"watergen", "frequency_sets", "register_spaces"};
    return names;
}

std::string binding_profile_list() {
    std::string s;
    for (const std::string& p : binding_profile_names())
        s += (s.empty() ? "" : ", ") + p;
    return s;
}

const BindingMap& default_binding_map() {
    return *binding_profile("watergen");
}

} // namespace watergen
