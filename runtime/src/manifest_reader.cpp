#include "manifest_reader.h"

#include <fstream>

namespace watergen::manifest {

namespace fs = std::filesystem;

std::optional<std::string> read_bytes(const fs::path& path, std::string* error,
                                      std::uintmax_t max_bytes) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
        *error = path.string() + ": " +
                 (fs::exists(path, ec) ? "not a regular file" : "no such file") +
                 "; expected a file of a watergen build";
        return std::nullopt;
    }
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec || size > max_bytes) {
        *error = path.string() + ": " +
                 (ec ? ec.message()
                     : std::to_string(size) + " bytes; expected at most " +
                           std::to_string(max_bytes) + " (no watergen build writes a larger one)");
        return std::nullopt;
    }
    std::ifstream in(path, std::ios::binary);
    std::string bytes(static_cast<size_t>(size), '\0');
    if (!in.read(bytes.data(), static_cast<std::streamsize>(size))) {
        *error = path.string() + ": cannot be read";
        return std::nullopt;
    }
    return bytes;
}

size_t estimated_bytes(const BuildVariant& v) {
    constexpr size_t kEntry = 64; // a map node or vector element and its bookkeeping
    size_t n = sizeof(BuildVariant) + v.scene.size() + v.key.size() + v.hash.size() +
               v.shader_directory.size() + v.block_name.size();
    for (const auto& [axis, choice] : v.choices)
        n += kEntry + axis.size() + choice.size();
    for (const auto& [kind, list] : v.files) {
        n += kEntry + kind.size();
        for (const std::string& f : list)
            n += kEntry + f.size();
    }
    for (const BlockParameter& p : v.parameters)
        n += sizeof(BlockParameter) + p.name.size() + p.type.size() + 8 * p.default_value.size();
    for (const TextureSlot& t : v.textures)
        n += sizeof(TextureSlot) + t.name.size() + t.type.size();
    for (const auto& [name, value] : v.folded_parameters)
        n += kEntry + name.size() + 8 * value.size();
    for (const std::string& r : v.removed_parameters)
        n += kEntry + r.size();
    n += kEntry * (v.specialization.size() + v.frozen.size() + v.passes.size());
    if (v.geometry)
        n += sizeof(VariantGeometry) +
             kEntry * (v.geometry->stages.size() + v.geometry->vertex_inputs.size());
    for (const auto& [name, value] : v.selector_uniforms)
        n += kEntry + name.size();
    for (const auto& [lang, file] : v.frozen)
        n += lang.size() + file.size();
    for (const auto& [name, pass] : v.passes) {
        n += sizeof(PassReference) + name.size() + pass.directory.size();
        for (const auto& [kind, list] : pass.files)
            for (const std::string& f : list)
                n += kEntry + kind.size() + f.size();
        for (const auto& [parameter, value] : pass.values)
            n += kEntry + parameter.size() + 8 * value.size();
    }
    return n;
}

std::string at(const std::string& path, size_t i) {
    return path + "[" + std::to_string(i) + "]";
}

BuildBindings read_bindings(ManifestReader& r, const json& bindings) {
    BuildBindings out;
    const std::string at_bindings = mk::top::kBindings;
    out.map = r.text(bindings, at_bindings, mk::bindings::kMap);
    const json* resources =
        r.get(bindings, at_bindings, mk::bindings::kResources, json::value_t::object, "an object");
    if (!resources) return out;
    std::string push; // the push-constant slot's name, once one is read
    for (const auto& [name, slot] : resources->items()) {
        const std::string path = at_bindings + "." + mk::bindings::kResources + "." + name;
        if (!slot.is_object()) {
            r.fail(path, "expected an object");
            return out;
        }
        MapSlot s;
        s.name = name;
        const std::string kind = r.text(slot, path, mk::resource::kKind);
        if (kind == "uniform_block")
            s.kind = DescriptorKind::UniformBuffer;
        else if (kind == "sampler")
            s.kind = DescriptorKind::Sampler;
        else if (kind == "texture")
            s.kind = DescriptorKind::SampledImage;
        else if (kind == "push_constant")
            s.kind = DescriptorKind::PushConstant;
        else if (!r.failed())
            r.fail(path + "." + mk::resource::kKind,
                   "'" + kind +
                       "'; expected uniform_block, sampler, texture or "
                       "push_constant");
        if (s.kind == DescriptorKind::PushConstant) {
            // One range at offset 0 holds one block
            // (generator/include/watergen/ir/emit/binding_map.h).
            if (!push.empty() && !r.failed())
                r.fail(path + "." + mk::resource::kKind,
                       "a second push_constant slot ('" + push + "' is one); expected at most one");
            push = name;
        } else {
            // A push constant has no set, binding or HLSL register: the keys are absent.
            s.set = r.u32(slot, path, mk::resource::kSet);
            s.binding = r.u32(slot, path, mk::resource::kBinding);
            s.hlsl_register = r.u32(slot, path, mk::resource::kHlslRegister);
            s.hlsl_space = r.u32(slot, path, mk::resource::kHlslSpace);
        }
        s.msl = r.u32(slot, path, mk::resource::kMsl);
        s.gl = r.u32(slot, path, mk::resource::kGl);
        if (r.failed()) return out;
        out.slots.push_back(std::move(s));
    }
    // The range's size, stated by a map with a push constant (and read only then: a map
    // without one has no range, whatever else it says).
    if (!push.empty()) {
        const uint32_t bytes = r.u32(bindings, at_bindings, mk::bindings::kPushConstantBytes);
        if (!r.failed() && (bytes < 4 || bytes > kMaxPushConstantRange || bytes % 4 != 0))
            r.fail(at_bindings + "." + mk::bindings::kPushConstantBytes,
                   std::to_string(bytes) + "; expected a multiple of 4 from 4 to " +
                       std::to_string(kMaxPushConstantRange) + " (the push-constant range of '" +
                       push + "')");
        out.push_constant_bytes = r.failed() ? 0 : bytes;
    }
    return out;
}

void read_file_lists(ManifestReader& r, const json& entry, const std::string& path,
                     std::map<std::string, std::vector<std::string>>& files) {
    // An entry's (namespace output) and a pass's "files" are spelled alike.
    const json* object = r.get(entry, path, mk::output::kFiles, json::value_t::object, "an object");
    if (!object) return;
    for (const auto& [kind, list] : object->items()) {
        const std::string where = path + "." + mk::output::kFiles + "." + kind;
        if (!list.is_array()) return r.fail(where, "expected an array");
        for (const json& p : list) {
            if (!p.is_string()) return r.fail(where, "expected paths");
            files[kind].push_back(p.get<std::string>());
        }
    }
}

void read_uniform_block(ManifestReader& r, const json& parent, const std::string& path,
                        BuildVariant& v) {
    // A manifest entry's "reflection" and a pass.json (at its top level) spell it alike.
    const json* block = r.get(parent, path, mk::reflection::kUniformBlock, json::value_t::object,
                              "an object", false);
    if (!block || block->empty()) return;
    const std::string bp =
        path.empty() ? mk::reflection::kUniformBlock : path + "." + mk::reflection::kUniformBlock;
    v.block_name = r.text(*block, bp, mk::uniform_block::kName);
    const json* members =
        r.get(*block, bp, mk::uniform_block::kMembers, json::value_t::array, "an array");
    if (!members) return;
    for (size_t i = 0; i < members->size(); ++i) {
        const json& m = (*members)[i];
        const std::string mp = at(bp + "." + mk::uniform_block::kMembers, i);
        BlockParameter p;
        p.name = r.text(m, mp, mk::member::kName);
        p.type = r.text(m, mp, mk::member::kType);
        if (m.contains(mk::member::kArraySize)) p.array_size = r.u32(m, mp, mk::member::kArraySize);
        p.offset = r.u32(m, mp, mk::member::kOffset);
        p.default_value = r.numbers(m, mp, mk::member::kDefault);
        if (const json* lo =
                r.get(m, mp, mk::member::kMin, json::value_t::number_float, "a number", false))
            p.min = lo->get<double>();
        if (const json* hi =
                r.get(m, mp, mk::member::kMax, json::value_t::number_float, "a number", false))
            p.max = hi->get<double>();
        if (const json* host =
                r.get(m, mp, mk::member::kHost, json::value_t::object, "an object", false)) {
            const std::string hp = mp + "." + mk::member::kHost;
            const std::string rule = r.text(*host, hp, mk::host::kRule);
            if (const auto known = host_rule_from_name(rule))
                p.host.rule = *known;
            else if (!r.failed())
                r.fail(hp + "." + mk::host::kRule,
                       "unknown rule '" + rule + "'; expected one of runtime/host_values.h's");
            if (const json* in =
                    r.get(*host, hp, mk::host::kInputs, json::value_t::array, "an array")) {
                for (const json& name : *in) {
                    if (!name.is_string()) {
                        r.fail(hp + "." + mk::host::kInputs, "expected an array of strings");
                        break;
                    }
                    p.host.inputs.push_back(name.get<std::string>());
                }
                if (!r.failed() && p.host.inputs.size() != host_rule_inputs(p.host.rule))
                    r.fail(hp + "." + mk::host::kInputs,
                           "expected " + std::to_string(host_rule_inputs(p.host.rule)) +
                               " parameters for rule " + rule);
            }
        }
        v.parameters.push_back(std::move(p));
    }
}

} // namespace watergen::manifest
