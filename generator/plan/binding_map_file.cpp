#include "watergen/plan/binding_map_file.h"

#include <cmath>

#include "watergen/plan/json_reader.h"
#include "watergen/water/binding_profiles.h"

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
    if (const BindingMap* profile = binding_profile(profile_or_path)) return *profile;
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
