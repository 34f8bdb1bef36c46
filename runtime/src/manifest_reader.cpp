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
    out.map = r.text(bindings, "bindings", "map");
    const json* resources =
        r.get(bindings, "bindings", "resources", json::value_t::object, "an object");
    if (!resources) return out;
    std::string push; // the push-constant slot's name, once one is read
    for (const auto& [name, slot] : resources->items()) {
        const std::string path = "bindings.resources." + name;
        if (!slot.is_object()) {
            r.fail(path, "expected an object");
            return out;
        }
        MapSlot s;
        s.name = name;
        const std::string kind = r.text(slot, path, "kind");
        if (kind == "uniform_block")
            s.kind = DescriptorKind::UniformBuffer;
        else if (kind == "sampler")
            s.kind = DescriptorKind::Sampler;
        else if (kind == "texture")
            s.kind = DescriptorKind::SampledImage;
        else if (kind == "push_constant")
            s.kind = DescriptorKind::PushConstant;
        else if (!r.failed())
            r.fail(path + ".kind", "'" + kind +
                                       "'; expected uniform_block, sampler, texture or "
                                       "push_constant");
        if (s.kind == DescriptorKind::PushConstant) {
            // One range at offset 0 holds one block (generator/ir/binding_map.h).
            if (!push.empty() && !r.failed())
                r.fail(path + ".kind",
                       "a second push_constant slot ('" + push + "' is one); expected at most one");
            push = name;
        } else {
            // A push constant has no set, binding or HLSL register: the keys are absent.
            s.set = r.u32(slot, path, "set");
            s.binding = r.u32(slot, path, "binding");
            s.hlsl_register = r.u32(slot, path, "hlsl_register");
            s.hlsl_space = r.u32(slot, path, "hlsl_space");
        }
        s.msl = r.u32(slot, path, "msl");
        s.gl = r.u32(slot, path, "gl");
        if (r.failed()) return out;
        out.slots.push_back(std::move(s));
    }
    // The range's size, stated by a map with a push constant (and read only then: a map
    // without one has no range, whatever else it says).
    if (!push.empty()) {
        const uint32_t bytes = r.u32(bindings, "bindings", "push_constant_bytes");
        if (!r.failed() && (bytes < 4 || bytes > kMaxPushConstantRange || bytes % 4 != 0))
            r.fail("bindings.push_constant_bytes",
                   std::to_string(bytes) + "; expected a multiple of 4 from 4 to " +
                       std::to_string(kMaxPushConstantRange) + " (the push-constant range of '" +
                       push + "')");
        out.push_constant_bytes = r.failed() ? 0 : bytes;
    }
    return out;
}

void read_file_lists(ManifestReader& r, const json& entry, const std::string& path,
                     std::map<std::string, std::vector<std::string>>& files) {
    const json* object = r.get(entry, path, "files", json::value_t::object, "an object");
    if (!object) return;
    for (const auto& [kind, list] : object->items()) {
        if (!list.is_array()) return r.fail(path + ".files." + kind, "expected an array");
        for (const json& p : list) {
            if (!p.is_string()) return r.fail(path + ".files." + kind, "expected paths");
            files[kind].push_back(p.get<std::string>());
        }
    }
}

void read_uniform_block(ManifestReader& r, const json& parent, const std::string& path,
                        BuildVariant& v) {
    const json* block =
        r.get(parent, path, "uniform_block", json::value_t::object, "an object", false);
    if (!block || block->empty()) return;
    const std::string bp = path.empty() ? "uniform_block" : path + ".uniform_block";
    v.block_name = r.text(*block, bp, "name");
    const json* members = r.get(*block, bp, "members", json::value_t::array, "an array");
    if (!members) return;
    for (size_t i = 0; i < members->size(); ++i) {
        const json& m = (*members)[i];
        const std::string mp = at(bp + ".members", i);
        BlockParameter p;
        p.name = r.text(m, mp, "name");
        p.type = r.text(m, mp, "type");
        if (m.contains("array_size")) p.array_size = r.u32(m, mp, "array_size");
        p.offset = r.u32(m, mp, "offset");
        p.default_value = r.numbers(m, mp, "default");
        if (const json* lo = r.get(m, mp, "min", json::value_t::number_float, "a number", false))
            p.min = lo->get<double>();
        if (const json* hi = r.get(m, mp, "max", json::value_t::number_float, "a number", false))
            p.max = hi->get<double>();
        v.parameters.push_back(std::move(p));
    }
}

} // namespace watergen::manifest
