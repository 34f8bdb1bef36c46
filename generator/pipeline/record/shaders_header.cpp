#include "watergen/pipeline/record/shaders_header.h"

#include <cstring>
#include <map>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <xxhash.h>

#include "watergen/ir/core/ir.h"
#include "watergen/ir/emit/uniform_layout.h"
#include "watergen/pipeline/output/json_document.h"
#include "watergen/pipeline/output/spill_file.h"
#include "watergen/pipeline/record/staged_tree.h"
#include "watergen/runtime/manifest_schema.h"

namespace watergen {

namespace {

using OJson = nlohmann::ordered_json;
namespace mk = manifest_schema;

// "default" -> "watergen_default": a namespace no keyword or other build's takes.
std::string namespace_of(const std::string& material) {
    std::string s = "watergen_";
    for (char c : material)
        s += ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9')) ? c : '_';
    return s;
}

// A C++ string literal of `text` (keys and names hold no quote or backslash; escaped anyway).
std::string literal(const std::string& text) {
    std::string s = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') s += '\\';
        s += c;
    }
    return s + "\"";
}

// A float as C++ writes it back to the same binary32 value.
std::string float_literal(double v) {
    std::string s = fmt::format("{}", static_cast<float>(v));
    if (s.find_first_of(".einf") == std::string::npos) s += ".0";
    return s + "f";
}

// Components of a block member's type as variant.json spells it (the IR's type_name); 0 for
// any type a block does not hold.
uint32_t components(const std::string& type) {
    for (Type t : {Type::Float, Type::Vec2, Type::Vec3, Type::Vec4})
        if (type == type_name(t)) return static_cast<uint32_t>(component_count(t));
    return 0;
}

// The C++ type of a member: Vec2..Vec4 for vectors, their padded element types in arrays.
std::string member_type(const std::string& type, bool element) {
    const std::string base = type == "float" ? "Float" : "Vec" + type.substr(3);
    if (element) return base + "Element";
    return type == "float" ? "float" : base;
}

// One value of `n` components as an initialiser: 1.0f or {1.0f, 2.0f}.
std::string initialiser(const std::vector<double>& values, size_t first, uint32_t n) {
    if (n == 1) return float_literal(values.at(first));
    std::string s = "{";
    for (uint32_t i = 0; i < n; ++i)
        s += (i ? ", " : "") + float_literal(values.at(first + i));
    return s + "}";
}

// The name a block struct is made with, before its interface has a number.
constexpr const char* kBlockPlaceholder = "WaterParams#";

// Texts the header writes once it has read every variant: in a spill file beside the output
// when it is written into a staging tree (a build has an interface for every few variants, each
// a few KB of struct), else held.
class HeldTexts {
  public:
    using Ref = SpillFile::Ref;
    explicit HeldTexts(const std::filesystem::path* scratch) {
        if (scratch) file_.emplace(*scratch, ".header-texts");
    }
    bool ok() const { return !file_ || file_->ok(); }
    std::optional<Ref> put(const std::string& text) {
        if (file_) return file_->append(text);
        held_.push_back(text);
        return Ref{held_.size() - 1, text.size()};
    }
    std::optional<std::string> get(Ref r) const {
        if (!file_) return held_.at(r.offset);
        std::string text;
        if (!file_->read(r.offset, r.size, text) || text.size() != r.size) return std::nullopt;
        return text;
    }

  private:
    std::optional<SpillFile> file_;
    std::vector<std::string> held_;
};

struct Interface {
    HeldTexts::Ref block;     // the uniform block's struct body and asserts, as written
    HeldTexts::Ref constants; // its specialization constants' initialiser list
    HeldTexts::Ref first;     // the first variant's scene and key, for the comment
    size_t constant_count = 0;
    size_t variants = 0;
};

// The struct of a variant.json's uniform block, named `name`; nullopt with *error.
std::optional<std::string> block_struct(const OJson& block, const std::string& name,
                                        std::string* error) {
    std::string body, asserts, hosts;
    uint32_t cursor = 0, pads = 0, host_count = 0;
    // A member with a host rule starts at what the shader reads for the defaults (the frame
    // of the default eye): the rule's value of them, as UniformWriter::pack computes it.
    std::map<std::string, std::vector<double>> defaults;
    for (const OJson& m : block.at(mk::uniform_block::kMembers))
        defaults[m.at(mk::member::kName).get<std::string>()] =
            m.at(mk::member::kDefault).get<std::vector<double>>();
    Frame frame;
    if (auto eye = defaults.find("eye_position"); eye != defaults.end() && eye->second.size() == 3)
        frame.centre = frame_centre_of(eye->second[0], eye->second[2]);
    const GivenValues given = [&](const std::string& n) -> const std::vector<double>* {
        auto it = defaults.find(n);
        return it == defaults.end() ? nullptr : &it->second;
    };
    for (const OJson& m : block.at(mk::uniform_block::kMembers)) {
        const std::string member = m.at(mk::member::kName).get<std::string>();
        const std::string type = m.at(mk::member::kType).get<std::string>();
        const uint32_t n = components(type);
        const uint32_t offset = m.at(mk::member::kOffset).get<uint32_t>();
        const uint32_t array = m.value(mk::member::kArraySize, 0u);
        std::vector<double> values = m.at(mk::member::kDefault).get<std::vector<double>>();
        std::string note;
        if (const auto host = m.find(mk::member::kHost); host != m.end()) {
            HostValue h;
            h.rule = host_rule_from_name(host->at(mk::host::kRule).get<std::string>())
                         .value_or(HostRule::Given);
            h.inputs = host->at(mk::host::kInputs).get<std::vector<std::string>>();
            std::string why;
            if (auto v = host_value(h, values, given, frame, &why); v && v->size() == values.size())
                values = *v;
            std::string from, inputs;
            for (const std::string& in : h.inputs) {
                from += (from.empty() ? " of " : ", ") + in;
                inputs += (inputs.empty() ? "" : ", ") + literal(in);
            }
            hosts += fmt::format("{}{{{}, {}, {}, {}, {}, {{{{{}}}}}}}", host_count++ ? ", " : "",
                                 literal(member), literal(host_rule_name(h.rule)), offset, n, array,
                                 inputs);
            note = fmt::format("    // {}{}: computed on the host in double "
                               "(UniformWriter::pack, runtime/host_values.h)\n",
                               host_rule_name(h.rule), from);
        }
        if (n == 0 || offset < cursor || offset % 4 != 0 ||
            values.size() != n * std::max(array, 1u)) {
            *error = "uniform block member '" + member + "' (" + type + " at " +
                     std::to_string(offset) + "): not a float member in order";
            return std::nullopt;
        }
        if (offset > cursor)
            body += fmt::format("    float pad{}[{}]{{}};\n", pads++, (offset - cursor) / 4);
        body += note;
        if (array) {
            std::string init;
            for (uint32_t e = 0; e < array; ++e)
                init += (e ? ", " : "") + std::string("{") + initialiser(values, e * n, n) + "}";
            body += fmt::format("    {} {}[{}] = {{{}}};\n", member_type(type, true), member, array,
                                init);
            cursor = offset + array * kArrayStride;
        } else {
            body += fmt::format("    {} {} = {};\n", member_type(type, false), member,
                                initialiser(values, 0, n));
            cursor = offset + 4 * n;
        }
        asserts += fmt::format("static_assert(offsetof({}, {}) == {});\n", name, member, offset);
    }
    const uint32_t size = block.at(mk::uniform_block::kSize).get<uint32_t>();
    if (size < cursor) {
        *error = "uniform block size " + std::to_string(size) + " below its members' end " +
                 std::to_string(cursor);
        return std::nullopt;
    }
    if (size > cursor) body += fmt::format("    float pad{}[{}]{{}};\n", pads, (size - cursor) / 4);
    body += fmt::format("    static constexpr std::array<HostMember, {}> kHostMembers{{{{{}}}}};\n",
                        host_count, hosts);
    if (size > 0) asserts += fmt::format("static_assert(sizeof({}) == {});\n", name, size);
    return fmt::format("struct {} {{\n{}}};\n{}", name, body, asserts);
}

std::string constants_of(const OJson& description, size_t* count) {
    std::string s;
    *count = 0;
    for (const OJson& c :
         description.value(mk::reflection::kSpecializationConstants, OJson::array()))
        for (const OJson& id : c.at(mk::member::kConstantIds)) {
            s += fmt::format("{}{{{}, {}}}", *count ? ", " : "", literal(c.at(mk::member::kName)),
                             id.get<uint32_t>());
            ++*count;
        }
    return s;
}

const char* kPrologue = R"(#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

// Types shared by every watergen build's header (defined once, whichever is included first).
#ifndef WATERGEN_SHADERS_HEADER_TYPES
#define WATERGEN_SHADERS_HEADER_TYPES
namespace watergen_shaders {
struct Vec2 { float x, y; };
struct Vec3 { float x, y, z; };
struct Vec4 { float x, y, z, w; };
// An array element: std140 and HLSL cbuffers start each one on a 16-byte register.
struct FloatElement { float value; float pad[3]{}; };
struct Vec2Element { Vec2 value; float pad[2]{}; };
struct Vec3Element { Vec3 value; float pad = 0; };
struct Vec4Element { Vec4 value; };
// Where the binding map puts a resource, in every target.
struct Slot { uint32_t set, binding, hlsl_register, hlsl_space, msl, gl; };
struct SpecializationConstant { const char* name; uint32_t constant_id; };
struct VariantInfo { const char* scene; const char* key; const char* hash; uint32_t interface_index; };
// A member the host computes in double each frame from values in world coordinates and seconds
// (watergen/runtime/host_values.h: host_value() with this rule and inputs, in the frame of
// frame_centre_of(eye)); its default is the value for the defaults. An array member's elements
// are 16 bytes apart.
struct HostMember {
    const char* name; const char* rule; uint32_t offset, components, elements;
    std::array<const char*, 5> inputs;
};
} // namespace watergen_shaders
#endif
)";

using WriteHeader = std::function<void(std::string_view)>;

// The header, written piece by piece: the manifest is parsed twice, once for its interfaces
// and once for the variant table, so neither the table nor the header is ever held whole (a
// build of thousands of variants writes megabytes of it); the interfaces' texts go to a spill
// file in `scratch` when given. False with *error.
bool header_of(const ReadJsonDocument& parse, const ReadOutputFile& read, const WriteHeader& write,
               const std::filesystem::path* scratch, std::string* error) {
    HeldTexts texts(scratch);
    if (!texts.ok()) {
        *error = "cannot write a spill file in " + scratch->string();
        return false;
    }
    std::string material, map_name;
    OJson resources;
    uint32_t push_constant_bytes = 0; // 0: the block is a uniform buffer
    // XXH3-128 of block + constants -> interface: the texts are kept once, in `texts`.
    std::map<std::pair<uint64_t, uint64_t>, size_t> interface_of_text;
    // A modes build's shader's description -> interface (each read once); a permutations
    // build's variants have a description each, so only the last is remembered.
    std::map<std::string, size_t> interface_of_dir;
    std::vector<Interface> interfaces;
    std::vector<uint32_t> variant_interface; // per variant, in the manifest's order
    bool modes = false;
    // The interface of a variant's description; `first` names the variant.
    auto interface_at = [&](const std::string& description,
                            const std::string& first) -> std::optional<size_t> {
        if (auto it = interface_of_dir.find(description); it != interface_of_dir.end())
            return it->second;
        const std::optional<std::string> text = read(description);
        if (!text) {
            *error = description + ": missing";
            return std::nullopt;
        }
        const OJson d = OJson::parse(*text, nullptr, false);
        if (d.is_discarded() || !d.contains(mk::reflection::kUniformBlock)) {
            *error = description + ": not a variant description";
            return std::nullopt;
        }
        // Written with a placeholder name: interfaces alike in everything but their number are
        // one, and the number is spelled when the header is written.
        auto block = block_struct(d[mk::reflection::kUniformBlock], kBlockPlaceholder, error);
        if (!block) {
            *error = description + ": " + *error;
            return std::nullopt;
        }
        size_t count = 0;
        const std::string constants = constants_of(d, &count);
        const std::string both = *block + "|" + constants;
        const XXH128_hash_t h = XXH3_128bits(both.data(), both.size());
        const auto [it, fresh] =
            interface_of_text.emplace(std::make_pair(h.high64, h.low64), interfaces.size());
        if (fresh) {
            const auto b = texts.put(*block), c = texts.put(constants), f = texts.put(first);
            if (!b || !c || !f) {
                *error = "cannot write a spill file in " + scratch->string();
                return std::nullopt;
            }
            interfaces.push_back({*b, *c, *f, count, 0});
        }
        if (!modes) interface_of_dir.clear();
        interface_of_dir.emplace(description, it->second);
        return it->second;
    };
    std::map<std::string, std::string> shader_description; // modes: directory -> variant.json
    JsonDocumentReader reader;
    reader.streamed = {mk::top::kShaders, mk::top::kVariants};
    reader.member = [&](const std::string& name, OJson&& value) {
        if (name == mk::top::kMaterial) material = value.value(mk::material::kName, "");
        if (name == mk::top::kBindings) {
            map_name = value.value(mk::bindings::kMap, "");
            resources = value.value(mk::bindings::kResources, OJson::object());
            push_constant_bytes = value.value(mk::bindings::kPushConstantBytes, 0u);
        }
        if (name == mk::top::kMode) modes = value.get<std::string>() != "permutations";
        return true;
    };
    reader.element = [&](const std::string& array, OJson&& e) {
        if (array == mk::top::kShaders) {
            const OJson& files = e[mk::output::kFiles][mk::files::kDescription];
            if (!files.is_array() || files.empty()) {
                *error = "manifest.json: a shader without a description file";
                return false;
            }
            shader_description[e.value(mk::output::kDirectory, "")] = files[0].get<std::string>();
            return true;
        }
        std::string description;
        if (modes) {
            const auto it = shader_description.find(e.value(mk::variant::kShader, ""));
            if (it != shader_description.end()) description = it->second;
        } else if (e[mk::output::kFiles][mk::files::kDescription].is_array() &&
                   !e[mk::output::kFiles][mk::files::kDescription].empty()) {
            description = e[mk::output::kFiles][mk::files::kDescription][0].get<std::string>();
        }
        if (description.empty()) {
            *error = "manifest.json: variant " + e.value(mk::variant::kKey, "") +
                     " names no description";
            return false;
        }
        const std::optional<size_t> i = interface_at(
            description, e.value(mk::variant::kScene, "") + " " + e.value(mk::variant::kKey, ""));
        if (!i) return false;
        ++interfaces[*i].variants;
        variant_interface.push_back(static_cast<uint32_t>(*i));
        return true;
    };
    auto parsed = [&](const JsonDocumentReader& r) {
        std::string why;
        const JsonReadEnd end = parse(r, &why);
        if (end == JsonReadEnd::Malformed) *error = "manifest.json: " + why;
        return end == JsonReadEnd::Done;
    };
    if (!parsed(reader)) return false;

    const std::string ns = namespace_of(material);
    write(fmt::format("// generated by watergen from the build of material '{}'; do not "
                      "edit. The build's\n// binding map, its uniform blocks as structs "
                      "and its variants (docs/engine-guide.md).\n",
                      material));
    write(kPrologue);
    write(fmt::format("\nnamespace {} {{\n\nusing namespace watergen_shaders;\n", ns));
    write(fmt::format("inline constexpr const char* kMaterial = {};\n", literal(material)));
    write(fmt::format("inline constexpr const char* kBindingMap = {};\n\n", literal(map_name)));
    write("// Every resource's place: set, binding, HLSL register, HLSL space, Metal index, GL "
          "unit.\nnamespace bindings {\n");
    for (const auto& [name, r] : resources.items())
        write(fmt::format("inline constexpr Slot {}{{{}, {}, {}, {}, {}, {}}}; // {}\n", name,
                          r.value(mk::resource::kSet, 0u), r.value(mk::resource::kBinding, 0u),
                          r.value(mk::resource::kHlslRegister, 0u),
                          r.value(mk::resource::kHlslSpace, 0u), r.value(mk::resource::kMsl, 0u),
                          r.value(mk::resource::kGl, 0u), r.value(mk::resource::kKind, "")));
    write("} // namespace bindings\n");
    if (push_constant_bytes)
        write(fmt::format("// The block is a push constant: one VkPushConstantRange of this many "
                          "bytes, vertex and\n// fragment stages, offset 0; every variant's block "
                          "fits in it.\ninline constexpr uint32_t kPushConstantBytes = {};\n",
                          push_constant_bytes));
    for (size_t i = 0; i < interfaces.size(); ++i) {
        const Interface& in = interfaces[i];
        auto block_text = texts.get(in.block), constants = texts.get(in.constants),
             first = texts.get(in.first);
        if (!block_text || !constants || !first) {
            *error = "cannot read a spill file in " + scratch->string();
            return false;
        }
        write(fmt::format("\n// Interface {}: {} variant{} (the first: {}).\n", i, in.variants,
                          in.variants == 1 ? "" : "s", *first));
        std::string block = std::move(*block_text);
        const std::string name = "WaterParams" + std::to_string(i);
        for (size_t at = block.find(kBlockPlaceholder); at != std::string::npos;
             at = block.find(kBlockPlaceholder, at))
            block.replace(at, std::strlen(kBlockPlaceholder), name);
        write(block);
        if (push_constant_bytes && block.find("struct " + name + " {") != std::string::npos)
            write(fmt::format("static_assert(sizeof({}) <= kPushConstantBytes);\n", name));
        write(fmt::format(
            "inline constexpr std::array<SpecializationConstant, {}> kConstants{}{{{{{}}}}};\n",
            in.constant_count, i, *constants));
    }
    write(fmt::format("\ninline constexpr std::array<VariantInfo, {}> kVariants{{{{\n",
                      variant_interface.size()));
    // The table, from the second parse: the variants again, in the same order.
    size_t k = 0;
    JsonDocumentReader table;
    table.streamed = {mk::top::kShaders, mk::top::kVariants};
    table.member = [](const std::string&, OJson&&) { return true; };
    table.element = [&](const std::string& array, OJson&& e) {
        if (array == mk::top::kShaders) return true;
        if (k == variant_interface.size()) return false;
        write(fmt::format("    {{{}, {}, {}, {}}},\n", literal(e.value(mk::variant::kScene, "")),
                          literal(e.value(mk::variant::kKey, "")),
                          literal(e.value(mk::variant::kHash, "")), variant_interface[k++]));
        return true;
    };
    if (!parsed(table) || k != variant_interface.size()) {
        if (error->empty()) *error = "manifest.json: changed while its header was written";
        return false;
    }
    write("}};\n");
    if (!interfaces.empty())
        write("\n// Calls f with interface i's uniform block at its defaults (f's result for each "
              "interface\n// must be of one type).\ntemplate <class F>\nconstexpr decltype(auto) "
              "with_interface(uint32_t i, F&& f) {\n    switch (i) {\n");
    for (size_t i = 0; i + 1 < interfaces.size(); ++i)
        write(fmt::format("    case {}:\n        return f(WaterParams{}{{}});\n", i, i));
    if (!interfaces.empty())
        write(fmt::format("    default:\n        return f(WaterParams{}{{}});\n    }}\n}}\n",
                          interfaces.size() - 1));
    write(fmt::format("\n}} // namespace {}\n", ns));
    return true;
}

} // namespace

std::optional<std::string> shaders_header(const ReadOutputFile& read, std::string* error) {
    const std::optional<std::string> manifest = read("manifest.json");
    if (!manifest) {
        *error = "manifest.json: missing";
        return std::nullopt;
    }
    std::string header;
    const bool made =
        header_of([&](const JsonDocumentReader& r,
                      std::string* why) { return read_json_document(*manifest, r, why); },
                  read, [&](std::string_view piece) { header.append(piece); }, nullptr, error);
    if (!made) return std::nullopt;
    return header;
}

std::optional<std::string> write_shaders_header(StagedTree& tree) {
    // The manifest read as it goes, never whole: a build of a few thousand variants writes
    // more than the tree reads back (tree.read's cap), and its text would be memory for nothing.
    // So is the header, written into the tree as it is made.
    std::FILE* manifest = std::fopen((tree.dir() / "manifest.json").c_str(), "rb");
    if (!manifest) return std::string(kShadersHeader) + ": manifest.json: missing";
    std::string why;
    StagedStream header = tree.stream(kShadersHeader);
    const bool made = header_of(
        [&](const JsonDocumentReader& r, std::string* w) {
            std::rewind(manifest);
            return read_json_document(manifest, r, w);
        },
        [&](const std::string& path) { return tree.read(path); },
        [&](std::string_view piece) { header.write(piece); }, &tree.dir(), &why);
    std::fclose(manifest);
    const std::optional<std::string> closed = header.close();
    if (!made) return std::string(kShadersHeader) + ": " + why;
    return closed;
}

} // namespace watergen
