#include "watergen/plan/binding_map_file.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <vector>

#include "watergen/plan/json_reader.h"
#include "watergen/plan/variant_space.h"
#include "watergen/water/binding_profiles.h"
#include "watergen/water/water_shader.h"

namespace watergen {
namespace {

// A whole number in [0, most] at `pointer`; `why` says where the bound comes from.
bool index_at(JsonReader& r, const std::string& pointer, uint32_t most, const std::string& why,
              uint32_t& out) {
    double v = 0;
    if (!r.number(pointer, v)) return false;
    if (v < 0 || v > most || std::floor(v) != v)
        return r.fail(pointer, "expected a whole number from 0 to " + std::to_string(most) + why +
                                   ", got " + r.at(pointer).dump());
    out = static_cast<uint32_t>(v);
    return true;
}

// Every resource a shader of this generator can read: the parameter block, the sampler, the
// profiles' textures, and the textures each choice's nodes read (a project's registered nodes
// too), each choice composed once with a variant its constraints allow.
const std::set<std::string>& readable_resources() {
    static const std::set<std::string> names = [] {
        std::set<std::string> out = {kParamsResource, kSamplerResource};
        for (const std::string& profile : binding_profile_names())
            for (const ResourceSlot& slot : binding_profile(profile)->slots)
                out.insert(slot.name);
        const auto& list = axes();
        auto read = [&](const Graph& g) {
            for (const TextureInput& t : g.textures())
                out.insert(t.name);
        };
        for (size_t a = 0; a < list.size(); ++a)
            for (const auto& choice : list[a].choices) {
                Variant v = default_variant();
                v.choices[a] = choice.name;
                // A choice the defaults rule out, with one other axis changed to allow it.
                for (size_t b = 0; b < list.size() && check_constraints(v); ++b)
                    for (const auto& other : list[b].choices) {
                        if (b == a) break;
                        Variant w = default_variant();
                        w.choices[a] = choice.name;
                        w.choices[b] = other.name;
                        if (!check_constraints(w)) {
                            v = w;
                            break;
                        }
                    }
                if (check_constraints(v)) continue;
                const WaterShader shader = build_water_shader(v);
                read(shader.fragment);
                if (shader.mesh)
                    for (const Graph* g : shader.mesh->graphs())
                        read(*g);
            }
        return out;
    }();
    return names;
}

// Whether the file at `path` starts, after blanks, with '{': a JSON document, not a program.
bool looks_like_json_object(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    for (char c; in.get(c);)
        if (c != ' ' && c != '\t' && c != '\n' && c != '\r') return c == '{';
    return false;
}

// The known name closest to `name` within 3 edits, for "did you mean"; "" when none is.
std::string closest(const std::string& name, const std::set<std::string>& known) {
    std::string best;
    size_t best_distance = 4;
    for (const std::string& k : known) {
        std::vector<size_t> row(k.size() + 1);
        for (size_t j = 0; j <= k.size(); ++j)
            row[j] = j;
        for (size_t i = 1; i <= name.size(); ++i) {
            size_t diagonal = row[0];
            row[0] = i;
            for (size_t j = 1; j <= k.size(); ++j) {
                const size_t up = row[j];
                row[j] = std::min(
                    {row[j] + 1, row[j - 1] + 1, diagonal + (name[i - 1] == k[j - 1] ? 0 : 1)});
                diagonal = up;
            }
        }
        if (row[k.size()] < best_distance) best_distance = row[k.size()], best = k;
    }
    return best;
}

} // namespace

std::optional<BindingMap> read_binding_map(const JsonSource& src, Diagnostics& ds) {
    JsonReader r(src, ds);
    if (!r.keys("", {"watergen_bindings", "base", "resources", "push_constant_bytes"},
                {"watergen_bindings", "resources"},
                "(a binding map; see docs/user-guide.md \"Binding maps\")"))
        return std::nullopt;
    double version = 0;
    if (!r.number("/watergen_bindings", version)) return std::nullopt;
    if (version != 1) {
        r.fail("/watergen_bindings",
               "expected 1 (the only format version), got " + r.at("/watergen_bindings").dump());
        return std::nullopt;
    }
    BindingMap map;
    map.name = src.file();
    if (r.has("/base")) {
        std::string base;
        if (!r.string_in("/base", binding_profile_names(), base)) return std::nullopt;
        map.slots = binding_profile(base)->slots;
    }
    if (!r.object("/resources", "resource names to their slots")) return std::nullopt;
    std::vector<std::string> pointers(map.slots.size()); // of each slot's entry; "" from the base
    for (const std::string& name : r.members("/resources")) {
        const std::string at = json_child("/resources", name);
        if (!r.keys(at, {"kind", "set", "binding", "hlsl_register", "hlsl_space", "msl", "gl"}, {}))
            return std::nullopt;
        const bool push = r.has(at + "/kind") && r.at(at + "/kind") == "push_constant";
        if (name.empty() ||
            name.find_first_not_of(
                "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") !=
                std::string::npos ||
            (name[0] >= '0' && name[0] <= '9')) {
            r.fail(at, "'" + name +
                           "' is not a shader identifier; expected the name a shader "
                           "declares (letters, digits, '_')");
            return std::nullopt;
        }
        ResourceSlot* slot = nullptr;
        for (size_t i = 0; i < map.slots.size(); ++i)
            if (map.slots[i].name == name) slot = &map.slots[i], pointers[i] = at;
        const bool fresh = slot == nullptr;
        if (push)
            for (const char* key : {"set", "binding", "hlsl_register", "hlsl_space"})
                if (r.has(at + "/" + key)) {
                    r.fail(at + "/" + key, "a push constant has no descriptor set, binding or "
                                           "HLSL register; expected only \"msl\" and \"gl\" "
                                           "beside \"kind\"");
                    return std::nullopt;
                }
        if (fresh) {
            if (!push && (!r.has(at + "/set") || !r.has(at + "/binding"))) {
                r.fail(at, "a resource the base does not place needs \"set\" and \"binding\"");
                return std::nullopt;
            }
            map.slots.push_back({name, default_resource_kind(name)});
            pointers.push_back(at);
            slot = &map.slots.back();
        }
        slot->origin = src.where(at);
        if (r.has(at + "/kind")) {
            std::string kind;
            if (!r.string_in(at + "/kind", {"uniform_block", "sampler", "texture", "push_constant"},
                             kind))
                return std::nullopt;
            slot->kind = *parse_resource_kind(kind);
        }
        struct Field {
            const char* key;
            uint32_t* value;
        };
        const Field fields[] = {{"set", &slot->set},
                                {"binding", &slot->binding},
                                {"hlsl_register", &slot->hlsl_register},
                                {"hlsl_space", &slot->hlsl_space},
                                {"msl", &slot->msl_index},
                                {"gl", &slot->gl_unit}};
        for (const Field& f : fields) {
            const bool set = std::string(f.key) == "set";
            if (r.has(at + "/" + f.key) &&
                !index_at(r, at + "/" + f.key, set ? kMaxSet : kMaxBindingIndex,
                          set ? " (Vulkan guarantees 4 bound descriptor sets)" : "", *f.value))
                return std::nullopt;
        }
        if (slot->kind == ResourceKind::PushConstant) // what a base gave it means nothing now
            slot->set = slot->binding = slot->hlsl_register = slot->hlsl_space = 0;
        // A name no node reads would only add a slot: a misspelt one would leave the resource
        // it meant where the base put it.
        if (fresh && !readable_resources().count(name)) {
            const std::string near = closest(name, readable_resources());
            std::string known;
            for (const std::string& k : readable_resources())
                known += (known.empty() ? "" : ", ") + k;
            r.fail(at, "'" + name + "' is not a resource any shader of this generator reads" +
                           (near.empty() ? "" : " (did you mean '" + near + "'?)") +
                           "; expected one of " + known);
            return std::nullopt;
        }
        if (fresh) {
            auto given = [&](const char* key) { return r.has(at + "/" + key); };
            if (!given("hlsl_register")) slot->hlsl_register = slot->binding;
            if (!given("hlsl_space")) slot->hlsl_space = slot->set;
            if (!given("msl")) slot->msl_index = slot->binding;
            if (!given("gl")) slot->gl_unit = slot->binding;
        }
    }
    if (r.has("/push_constant_bytes")) {
        uint32_t bytes = 0;
        if (!index_at(r, "/push_constant_bytes", kMaxPushConstantBytes, " (no device pushes more)",
                      bytes))
            return std::nullopt;
        // 16: the block is padded to whole 16-byte registers (as every device's limit is).
        if (bytes == 0 || bytes % 16 != 0) {
            r.fail("/push_constant_bytes",
                   "expected a multiple of 16 bytes from 16 (the block is whole 16-byte "
                   "registers), got " +
                       std::to_string(bytes));
            return std::nullopt;
        }
        map.push_constant_bytes = bytes;
    }
    if (const auto clash = map.conflict()) {
        const std::string& at = pointers[clash->later];
        ds.push_back(at.empty() ? Diagnostic{Severity::Error, src.file(), 0, 0, "", clash->message}
                                : src.error(at, clash->message));
        return std::nullopt;
    }
    return map;
}

std::optional<BindingMap> load_binding_map(const std::string& profile_or_path, Diagnostics& ds) {
    if (const BindingMap* profile = binding_profile(profile_or_path)) {
        // A map file of the profile's name here would be shadowed by the profile without a
        // word. (Another file of that name, a project's generator called watergen, is not one.)
        if (looks_like_json_object(profile_or_path)) {
            ds.push_back({Severity::Error, profile_or_path, 0, 0, "",
                          "'" + profile_or_path +
                              "' names both a binding profile and a file "
                              "here; write ./" +
                              profile_or_path + " for the file, or rename it"});
            return std::nullopt;
        }
        return *profile;
    }
    Diagnostic error;
    const auto src = JsonSource::load(profile_or_path, &error);
    if (!src) {
        if (profile_or_path.find_first_of("/.") == std::string::npos)
            error.message +=
                " (not a profile either; the profiles are " + binding_profile_list() + ")";
        ds.push_back(error);
        return std::nullopt;
    }
    return read_binding_map(*src, ds);
}

nlohmann::ordered_json binding_map_json(const BindingMap& map) {
    nlohmann::ordered_json resources = nlohmann::ordered_json::object();
    for (const ResourceSlot& s : map.slots) {
        if (s.kind == ResourceKind::PushConstant) { // no set, binding or register
            resources[s.name] = {
                {"kind", to_string(s.kind)}, {"msl", s.msl_index}, {"gl", s.gl_unit}};
            continue;
        }
        resources[s.name] = {{"kind", to_string(s.kind)},
                             {"set", s.set},
                             {"binding", s.binding},
                             {"hlsl_register", s.hlsl_register},
                             {"hlsl_space", s.hlsl_space},
                             {"msl", s.msl_index},
                             {"gl", s.gl_unit}};
    }
    nlohmann::ordered_json j = {{"watergen_bindings", 1}, {"resources", resources}};
    if (map.push_constant()) j["push_constant_bytes"] = map.push_constant_bytes;
    return j;
}

} // namespace watergen
