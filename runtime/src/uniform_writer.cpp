// Typed parameter values of one variant, packed at the offsets a language's reflection gives.
#include "watergen/runtime/uniform_writer.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace watergen {

namespace {

std::string type_of(const BlockParameter& p) {
    return p.array_size ? p.type + "[" + std::to_string(p.array_size) + "]" : p.type;
}

std::string given_type(size_t n) {
    switch (n) {
    case 1:
        return "float";
    case 2:
        return "vec2";
    case 3:
        return "vec3";
    case 4:
        return "vec4";
    default:
        return std::to_string(n) + " floats";
    }
}

std::string numbers(const std::vector<double>& v) {
    std::string out;
    for (double x : v) {
        char buf[32];
        std::snprintf(buf, sizeof(buf), "%g", x);
        out += (out.empty() ? "" : ", ") + std::string(buf);
    }
    return v.size() == 1 ? out : "(" + out + ")";
}

std::string variant_name(const BuildVariant& v) {
    return "variant " + v.key + " (scene " + v.scene + ")";
}

// "vec2[8]" -> "vec2".
std::string base_type(const std::string& type) {
    return type.substr(0, type.find('['));
}

// Setting a parameter the scene folded: the folded value again is a no-op that says so,
// another value an error naming the value, the scene and the variant.
Write folded_write(const BuildVariant& v, const std::string& name,
                   const std::vector<double>& folded, std::span<const double> values) {
    Write w;
    const bool same = folded.size() == values.size() &&
                      std::equal(values.begin(), values.end(), folded.begin(),
                                 [](double a, double b) { return float(a) == float(b); });
    if (same) {
        w.ok = true;
        w.note = "parameter '" + name + "' was folded to " + numbers(folded) + " by scene " +
                 v.scene + "; the same value is a no-op";
    } else {
        w.error = "parameter '" + name + "' was folded to " + numbers(folded) + " by scene " +
                  v.scene + " (" + variant_name(v) + "); the shader cannot take " +
                  numbers(std::vector<double>(values.begin(), values.end())) +
                  ": change the scene's facts or leave it unset";
    }
    return w;
}

} // namespace

uint32_t type_components(const std::string& type) {
    if (type == "float" || type == "int" || type == "uint") return 1;
    if (type == "vec2") return 2;
    if (type == "vec3") return 3;
    if (type == "vec4") return 4;
    return 0;
}

UniformWriter::UniformWriter(const BuildVariant& variant) : variant_(variant) {
    for (const BlockParameter& p : variant.parameters) {
        Slot s{&p, p.default_value};
        if (const auto sel = variant.selector_uniforms.find(p.name);
            sel != variant.selector_uniforms.end())
            s.values.assign(1, sel->second);
        values_[p.name] = std::move(s);
    }
}

std::optional<std::vector<float>> UniformWriter::value(const std::string& name) const {
    const auto it = values_.find(name);
    if (it == values_.end()) return std::nullopt;
    return std::vector<float>(it->second.values.begin(), it->second.values.end());
}

bool UniformWriter::computed(const std::string& name) const {
    const auto it = values_.find(name);
    return it != values_.end() && host_rule_computed(it->second.parameter->host.rule);
}

Frame UniformWriter::frame() const {
    if (frame_) return *frame_;
    Frame f{{}, origin_};
    if (const auto it = values_.find("eye_position");
        it != values_.end() && it->second.parameter->host.rule == HostRule::FramePoint &&
        it->second.values.size() == 3)
        f.centre = frame_centre_of(it->second.values[0], it->second.values[2]);
    return f;
}

Write UniformWriter::set(const std::string& name, std::span<const float> values) {
    const std::vector<double> wide(values.begin(), values.end());
    return set(name, std::span<const double>(wide));
}

Write UniformWriter::set(const std::string& name, std::span<const double> values) {
    Write w;
    const auto it = values_.find(name);
    if (it == values_.end()) {
        for (const auto& [member, slot] : values_) {
            const auto& in = slot.parameter->host.inputs;
            if (std::find(in.begin(), in.end(), name) == in.end()) continue;
            for (double v : values)
                if (!std::isfinite(v)) {
                    w.error = "parameter '" + name + "': value is not finite";
                    return w;
                }
            host_inputs_[name].assign(values.begin(), values.end());
            w.ok = true;
            return w;
        }
        if (const auto f = variant_.folded_parameters.find(name);
            f != variant_.folded_parameters.end())
            return folded_write(variant_, name, f->second, values);
        const auto& removed = variant_.removed_parameters;
        if (std::find(removed.begin(), removed.end(), name) != removed.end()) {
            w.ok = true;
            w.note = "parameter '" + name + "' is not read by " + variant_name(variant_) +
                     " (removed_parameters); the value has no effect";
            return w;
        }
        std::string known;
        for (const auto& [n, s] : values_)
            known += (known.empty() ? "" : ", ") + n;
        w.error = "unknown parameter '" + name + "' (given " + given_type(values.size()) +
                  "): " + variant_name(variant_) + " has " + known;
        return w;
    }
    Slot& slot = it->second;
    const BlockParameter& p = *slot.parameter;
    // A fixed value a host rule still reads (the scene fixed time = 0): the member stays, the
    // value does not change.
    if (const auto f = variant_.folded_parameters.find(name); f != variant_.folded_parameters.end())
        return folded_write(variant_, name, f->second, values);
    if (host_rule_computed(p.host.rule)) {
        std::string from;
        for (const std::string& in : p.host.inputs)
            from += (from.empty() ? "" : ", ") + in;
        w.error = "parameter '" + name + "' is computed on the host (" +
                  host_rule_name(p.host.rule) + (from.empty() ? "" : " of " + from) + "); set " +
                  (from.empty() ? "the eye position" : from) + " instead";
        return w;
    }
    if (variant_.selector_uniforms.count(name)) {
        w.error = "parameter '" + name + "' selects the variant (branching build mode); select " +
                  "another variant instead of setting it";
        return w;
    }
    const uint32_t comps = type_components(p.type);
    const size_t expected = size_t(comps) * std::max<uint32_t>(p.array_size, 1);
    if (comps == 0 || p.type == "int" || p.type == "uint" || values.size() != expected) {
        w.error = "parameter '" + name + "' is " + type_of(p) + "; given " +
                  given_type(values.size()) +
                  (p.array_size ? " (expected " + std::to_string(expected) + " floats)" : "");
        return w;
    }
    for (double v : values)
        if (!std::isfinite(v) || !std::isfinite(float(v))) {
            w.error = "parameter '" + name + "' (" + type_of(p) + "): value is not finite";
            return w;
        }
    // The generator folded and bounded the shader for values within the declared range (an
    // interval it proved may no longer hold outside it), so a value outside is refused rather
    // than drawn wrong. Compared as floats, so the float nearest a bound (what an engine holding
    // the bound in a float passes) is accepted.
    for (size_t k = 0; k < values.size(); ++k)
        if (float(values[k]) < float(p.min) || float(values[k]) > float(p.max)) {
            w.error = "parameter '" + name + "' (" + type_of(p) +
                      "): " + (values.size() > 1 ? "value " + std::to_string(k) + ", " : "") +
                      numbers({values[k]}) + ", is outside its range [" + numbers({p.min}) + ", " +
                      numbers({p.max}) + "]";
            return w;
        }
    slot.values.assign(values.begin(), values.end());
    w.ok = true;
    return w;
}

std::optional<std::vector<uint8_t>> UniformWriter::pack(const Reflection& reflection,
                                                        std::string* error) const {
    const DescriptorBinding* block = nullptr;
    for (const DescriptorBinding& b : reflection.bindings)
        if (b.kind == DescriptorKind::UniformBuffer &&
            (b.name == variant_.block_name || variant_.block_name.empty()))
            block = &b;
    // A binding map that makes the block a push constant keeps its layout (std140 / cbuffer
    // offsets, generator/include/watergen/ir/emit/binding_map.h): the same bytes, pushed instead of
    // bound.
    if (const auto& push = reflection.push_constant;
        !block && push && (push->name == variant_.block_name || variant_.block_name.empty()))
        block = &*push;
    if (!block) {
        if (variant_.parameters.empty()) return std::vector<uint8_t>{};
        *error = "the reflection has no uniform block or push-constant block '" +
                 variant_.block_name + "' (" + variant_name(variant_) + ")";
        return std::nullopt;
    }
    // The values the shader reads: each host rule applied in double (host_values.h).
    const Frame frame = this->frame();
    const GivenValues given = [&](const std::string& name) -> const std::vector<double>* {
        if (const auto it = values_.find(name); it != values_.end()) return &it->second.values;
        if (const auto it = host_inputs_.find(name); it != host_inputs_.end()) return &it->second;
        return nullptr;
    };
    std::map<std::string, std::vector<double>> host;
    for (const auto& [name, slot] : values_) {
        if (slot.parameter->host.rule == HostRule::Given) continue;
        std::string why;
        auto v = host_value(slot.parameter->host, slot.values, given, frame, &why);
        if (!v) {
            *error = "parameter '" + name + "' of " + variant_name(variant_) + ": " + why +
                     (why.find("has no value") != std::string::npos ? "; set it" : "");
            return std::nullopt;
        }
        host[name] = std::move(*v);
    }
    // size_t: a block_size near 2^32 must not wrap to an empty buffer the members then overrun.
    std::vector<uint8_t> bytes((size_t(block->block_size) + 15) / 16 * 16, 0);
    for (const UniformMember& m : block->members) {
        const auto it = values_.find(m.name);
        if (it == values_.end()) {
            *error = "reflected member '" + m.name + "' of block " + block->name +
                     " is not a parameter of " + variant_name(variant_);
            return std::nullopt;
        }
        const BlockParameter& p = *it->second.parameter;
        const std::string base = base_type(m.type);
        const uint32_t comps = type_components(base);
        const uint32_t count = std::max<uint32_t>(m.array_size, 1);
        const uint32_t stride = m.array_size ? m.array_stride : comps * 4;
        const bool fits =
            comps != 0 && base == p.type && m.array_size == p.array_size && stride >= comps * 4 &&
            m.size == (m.array_size ? count * stride : comps * 4) &&
            uint64_t(m.offset) + uint64_t(count - 1) * stride + comps * 4 <= block->block_size;
        if (!fits) {
            *error = "reflected member '" + m.name + "' of block " + block->name + " (" + m.type +
                     ", offset " + std::to_string(m.offset) + ", size " + std::to_string(m.size) +
                     ", stride " + std::to_string(m.array_stride) +
                     ") does not fit parameter type " + type_of(p);
            return std::nullopt;
        }
        const auto computed = host.find(m.name);
        const std::vector<double>& values =
            computed != host.end() ? computed->second : it->second.values;
        if (values.size() != size_t(comps) * count) {
            *error = "parameter '" + m.name + "' has " + std::to_string(values.size()) +
                     " values in the manifest; " + type_of(p) + " needs " +
                     std::to_string(comps * count);
            return std::nullopt;
        }
        for (uint32_t e = 0; e < count; ++e)
            for (uint32_t c = 0; c < comps; ++c) {
                const float f = static_cast<float>(values[size_t(e) * comps + c]);
                uint8_t* at = bytes.data() + m.offset + size_t(e) * stride + c * 4;
                if (base == "int") {
                    const int32_t i = static_cast<int32_t>(f);
                    std::memcpy(at, &i, 4);
                } else if (base == "uint") {
                    const uint32_t u = static_cast<uint32_t>(f);
                    std::memcpy(at, &u, 4);
                } else {
                    std::memcpy(at, &f, 4);
                }
            }
    }
    return bytes;
}

} // namespace watergen
