#include "watergen/runtime/reflection.h"

#include <cstdint>
#include <limits>

#include <nlohmann/json.hpp>

#include "json_limits.h"

namespace watergen {
namespace {

// What the generator's reflection of one stage can hold (toolchain/ reflects SPIRV-Cross's view
// of a generated shader): one uniform block of the material's parameters (the node catalog
// declares under a hundred; each is a member) and one binding per texture a node samples
// (under ten), all in set 0; a handful of stage inputs and outputs; a specialization constant
// per selector component in the specialized mode (under a hundred). Each limit is ten times
// that or more, so a real file never meets one; a file past one is not a watergen reflection,
// and reading it on would only spend memory (a DOM of 100,000 bindings) or hand a driver
// descriptor set layouts it cannot make.
constexpr size_t kMaxBindings = 64;
constexpr size_t kMaxMembers = 1024;
constexpr size_t kMaxStageVariables = 64;
constexpr size_t kMaxSpecializationConstants = 1024;
// Vulkan guarantees 4 bound descriptor sets (maxBoundDescriptorSets), and 1024 binding numbers
// per set is far beyond a shader with kMaxBindings bindings.
constexpr uint32_t kMaxSet = 3;
constexpr uint32_t kMaxBinding = 1023;
// A uniform or storage block: Vulkan guarantees 16 KiB uniform buffers (maxUniformBufferRange);
// the material's block is well under 1 KiB. UniformWriter::pack() allocates block_size bytes.
constexpr uint32_t kMaxBlockSize = 1u << 16;
// The text as a whole: 1 MiB, and its values, depth and strings (json_limits.h): a real file is
// a few KB of at most 5 levels (object, bindings, binding, members, member).
constexpr size_t kMaxReflectionBytes = size_t(1) << 20;
constexpr json_limits::Limits kLimits{size_t(1) << 16, 8, 4096};

using nlohmann::json;

constexpr ShaderStage kStages[] = {ShaderStage::Vertex, ShaderStage::Fragment, ShaderStage::Compute,
                                   ShaderStage::TessControl, ShaderStage::TessEvaluation};
constexpr DescriptorKind kKinds[] = {DescriptorKind::UniformBuffer, DescriptorKind::StorageBuffer,
                                     DescriptorKind::SampledImage, DescriptorKind::Sampler,
                                     DescriptorKind::CombinedImageSampler};
// Vulkan guarantees 128 bytes of push constants (maxPushConstantsSize); the largest any device
// reports is 4096 (Apple's).
constexpr uint32_t kMaxPushConstantBytes = 4096;

json to_json(const UniformMember& m) {
    json j{{"name", m.name}, {"type", m.type}, {"offset", m.offset}, {"size", m.size}};
    if (m.array_size) { // absent for the scalars and vectors of older files
        j["array_size"] = m.array_size;
        j["array_stride"] = m.array_stride;
    }
    return j;
}

json to_json(const StageVariable& v) {
    return json{{"name", v.name}, {"location", v.location}, {"type", v.type}};
}

json to_json(const SpecializationConstant& c) {
    return json{{"id", c.id},   {"name", c.name}, {"type", c.type}, {"default", c.default_value},
                {"min", c.min}, {"max", c.max}};
}

json to_json(const DescriptorBinding& b) {
    json members = json::array();
    for (const auto& m : b.members)
        members.push_back(to_json(m));
    return json{{"name", b.name},
                {"set", b.set},
                {"binding", b.binding},
                {"kind", to_string(b.kind)},
                {"image_dim", b.image_dim},
                {"block_size", b.block_size},
                {"members", std::move(members)}};
}

template <class T> json to_json_array(const std::vector<T>& items) {
    json a = json::array();
    for (const auto& item : items)
        a.push_back(to_json(item));
    return a;
}

// Reads one JSON object, recording the first problem as "<key path>: <what was expected>".
// Every accessor checks the type first, so nlohmann never gets to throw.
class Reader {
  public:
    Reader(const json& object, std::string path, std::string* error)
        : object_(object), path_(std::move(path)), error_(error) {}

    bool string(const char* key, std::string& out, bool required = true) {
        const json* v = find(key, required, "a string");
        if (!v) return !required && !failed_;
        if (!v->is_string()) return fail(key, "expected a string");
        out = v->get<std::string>();
        return true;
    }

    bool u32(const char* key, uint32_t& out, bool required = true,
             uint32_t max = std::numeric_limits<uint32_t>::max()) {
        const json* v = find(key, required, "an unsigned 32-bit integer");
        if (!v) return !required && !failed_;
        if (!v->is_number_unsigned() || v->get<uint64_t>() > std::numeric_limits<uint32_t>::max())
            return fail(key, "expected an unsigned 32-bit integer");
        if (v->get<uint64_t>() > max)
            return fail(key, std::to_string(v->get<uint64_t>()) + "; expected at most " +
                                 std::to_string(max));
        out = static_cast<uint32_t>(v->get<uint64_t>());
        return true;
    }

    bool number(const char* key, double& out) {
        const json* v = find(key, true, "a number");
        if (!v) return false;
        if (!v->is_number()) return fail(key, "expected a number");
        out = v->get<double>();
        return true;
    }

    template <class Enum, size_t N>
    bool enumeration(const char* key, const Enum (&values)[N], Enum& out) {
        std::string text;
        if (!string(key, text)) return false;
        std::string expected = "expected one of";
        for (size_t i = 0; i < N; ++i) {
            if (text == to_string(values[i])) {
                out = values[i];
                return true;
            }
            expected += std::string(i ? ", " : " ") + to_string(values[i]);
        }
        return fail(key, expected + "; got \"" + text + "\"");
    }

    // Calls read(element_reader, item) for each object in the array at `key`.
    template <class T, class Fn>
    bool array(const char* key, std::vector<T>& out, Fn read, size_t max_items,
               bool required = true) {
        const json* v = find(key, required, "an array");
        if (!v) return !required && !failed_;
        if (!v->is_array()) return fail(key, "expected an array");
        if (v->size() > max_items)
            return fail(key, std::to_string(v->size()) + " items; expected at most " +
                                 std::to_string(max_items) + " (a watergen shader has far fewer)");
        out.clear();
        for (size_t i = 0; i < v->size(); ++i) {
            const std::string element = join(key) + "[" + std::to_string(i) + "]";
            const json& item = (*v)[i];
            if (!item.is_object()) {
                *error_ = element + ": expected an object";
                return false;
            }
            T value{};
            Reader r(item, element, error_);
            if (!read(r, value)) return false;
            out.push_back(std::move(value));
        }
        return true;
    }

    // Calls read(object_reader, value) for the optional object at `key`.
    template <class T, class Fn> bool object(const char* key, std::optional<T>& out, Fn read) {
        const json* v = find(key, false, "an object");
        if (!v) return !failed_;
        if (!v->is_object()) return fail(key, "expected an object");
        T value{};
        Reader r(*v, join(key), error_);
        if (!read(r, value)) return false;
        out = std::move(value);
        return true;
    }

    bool fail(const char* key, const std::string& what) {
        *error_ = join(key) + ": " + what;
        failed_ = true;
        return false;
    }

  private:
    std::string join(const char* key) const { return path_.empty() ? key : path_ + "." + key; }

    const json* find(const char* key, bool required, const char* expected) {
        const auto it = object_.find(key);
        if (it != object_.end()) return &*it;
        if (required) fail(key, std::string("missing, expected ") + expected);
        return nullptr;
    }

    const json& object_;
    std::string path_;
    std::string* error_;
    bool failed_ = false;
};

bool read_member(Reader& r, UniformMember& m) {
    return r.string("name", m.name) && r.string("type", m.type) && r.u32("offset", m.offset) &&
           r.u32("size", m.size) && r.u32("array_size", m.array_size, false) &&
           r.u32("array_stride", m.array_stride, false);
}

bool read_variable(Reader& r, StageVariable& v) {
    return r.string("name", v.name) && r.u32("location", v.location) && r.string("type", v.type);
}

bool read_specialization_constant(Reader& r, SpecializationConstant& c) {
    return r.u32("id", c.id) && r.string("name", c.name) && r.string("type", c.type) &&
           r.number("default", c.default_value) && r.number("min", c.min) && r.number("max", c.max);
}

// A binding's fields, its kind one of `kinds`.
template <size_t N>
bool read_block(Reader& r, DescriptorBinding& b, const DescriptorKind (&kinds)[N]) {
    // image_dim, block_size and members only matter for some kinds, so they may be omitted.
    return r.string("name", b.name) && r.u32("set", b.set, true, kMaxSet) &&
           r.u32("binding", b.binding, true, kMaxBinding) && r.enumeration("kind", kinds, b.kind) &&
           r.string("image_dim", b.image_dim, false) &&
           r.u32("block_size", b.block_size, false, kMaxBlockSize) &&
           r.array("members", b.members, read_member, kMaxMembers, false);
}

// A descriptor: never a push constant (that is Reflection::push_constant, not a binding).
bool read_binding(Reader& r, DescriptorBinding& b) {
    return read_block(r, b, kKinds);
}

// A push-constant block: a block's name, size and members at set 0, binding 0, kind
// push_constant, within the bytes any device can push.
bool read_push_constant(Reader& r, DescriptorBinding& b) {
    constexpr DescriptorKind kPush[] = {DescriptorKind::PushConstant};
    if (!read_block(r, b, kPush)) return false;
    if (b.set != 0 || b.binding != 0)
        return r.fail(b.set != 0 ? "set" : "binding",
                      std::to_string(b.set != 0 ? b.set : b.binding) +
                          "; a push-constant block has set 0 and binding 0");
    if (b.block_size == 0 || b.block_size > kMaxPushConstantBytes)
        return r.fail("block_size", std::to_string(b.block_size) + "; expected 1 to " +
                                        std::to_string(kMaxPushConstantBytes) +
                                        " bytes of push constants");
    return true;
}

} // namespace

const char* to_string(ShaderStage s) {
    switch (s) {
    case ShaderStage::Vertex:
        return "vertex";
    case ShaderStage::Fragment:
        return "fragment";
    case ShaderStage::Compute:
        return "compute";
    case ShaderStage::TessControl:
        return "tess_control";
    case ShaderStage::TessEvaluation:
        return "tess_evaluation";
    }
    return "unknown";
}

const char* to_string(DescriptorKind k) {
    switch (k) {
    case DescriptorKind::UniformBuffer:
        return "uniform_buffer";
    case DescriptorKind::StorageBuffer:
        return "storage_buffer";
    case DescriptorKind::SampledImage:
        return "sampled_image";
    case DescriptorKind::Sampler:
        return "sampler";
    case DescriptorKind::CombinedImageSampler:
        return "combined_image_sampler";
    case DescriptorKind::PushConstant:
        return "push_constant";
    }
    return "unknown";
}

std::string reflection_to_json(const Reflection& r) {
    // nlohmann::json keeps object keys in a std::map, so the output is sorted by key.
    json doc{{"stage", to_string(r.stage)},
             {"entry_point", r.entry_point},
             {"bindings", to_json_array(r.bindings)},
             {"inputs", to_json_array(r.inputs)},
             {"outputs", to_json_array(r.outputs)}};
    // Only when there are some: a shader without them keeps the form it always had.
    if (!r.specialization_constants.empty())
        doc["specialization_constants"] = to_json_array(r.specialization_constants);
    if (r.push_constant) doc["push_constant"] = to_json(*r.push_constant);
    // replace: a name that is not UTF-8 must not make serialisation throw.
    return doc.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

std::optional<Reflection> reflection_from_json(const std::string& text, std::string* error) {
    std::string scratch;
    if (!error) error = &scratch;
    error->clear();
    if (text.size() > kMaxReflectionBytes) {
        *error = "(root): " + std::to_string(text.size()) + " bytes; expected at most " +
                 std::to_string(kMaxReflectionBytes) + " (a watergen reflection is a few KB)";
        return std::nullopt;
    }
    bool syntax_error = false;
    if (const std::string over = json_limits::check(text, kLimits, &syntax_error); !over.empty()) {
        *error = "(root): " + over + "; expected a watergen reflection (a few KB)";
        return std::nullopt;
    }
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::exception& e) {
        // what() is "[json.exception.parse_error.101] parse error at line 1, column 5: ...".
        std::string what = e.what();
        const size_t bracket = what.find("] ");
        if (bracket != std::string::npos) what = what.substr(bracket + 2);
        *error = "(root): expected valid JSON; " + what;
        return std::nullopt;
    }
    if (!doc.is_object()) {
        *error = "(root): expected an object";
        return std::nullopt;
    }
    Reflection r;
    Reader reader(doc, "", error);
    const bool ok =
        reader.enumeration("stage", kStages, r.stage) &&
        reader.string("entry_point", r.entry_point) &&
        reader.array("bindings", r.bindings, read_binding, kMaxBindings) &&
        reader.array("inputs", r.inputs, read_variable, kMaxStageVariables) &&
        reader.array("outputs", r.outputs, read_variable, kMaxStageVariables) &&
        reader.array("specialization_constants", r.specialization_constants,
                     read_specialization_constant, kMaxSpecializationConstants, false) &&
        reader.object("push_constant", r.push_constant, read_push_constant);
    if (!ok) return std::nullopt;
    return r;
}

const char* stage_tag(ShaderStage s) {
    switch (s) {
    case ShaderStage::Vertex:
        return "vert";
    case ShaderStage::Fragment:
        return "frag";
    case ShaderStage::Compute:
        return "comp";
    case ShaderStage::TessControl:
        return "tesc";
    case ShaderStage::TessEvaluation:
        return "tese";
    }
    return "frag";
}

} // namespace watergen
