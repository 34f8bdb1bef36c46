#include "watergen/ir/emit/uniform_layout.h"

#include <algorithm>
#include <cstring>

namespace watergen {

namespace {

uint32_t alignment_of(const Parameter& p) {
    if (p.array_size) return kArrayStride;
    switch (p.type) {
    case Type::Vec2:
        return 8;
    case Type::Vec3:
    case Type::Vec4:
        return 16;
    default:
        return 4;
    }
}

// 4-byte words a member occupies. An array takes whole registers, its last element's tail too:
// std140 places nothing there (HLSL could, but then the two layouts would differ).
uint32_t words_of(const Parameter& p) {
    return p.array_size ? p.array_size * (kArrayStride / 4)
                        : static_cast<uint32_t>(component_count(p.type));
}

} // namespace

UniformLayout layout_uniforms(const std::vector<Parameter>& parameters, Diagnostics& diagnostics) {
    std::vector<const Parameter*> order;
    for (const auto& p : parameters) {
        if (p.specialization) continue; // a specialization constant (ir/specialization.h)
        if (!is_float_numeric(p.type)) {
            diagnostics.push_back({Severity::Error, "", 0, 0, p.origin,
                                   "parameter '" + p.name + "' has type " + type_name(p.type) +
                                       "; uniform blocks hold float scalars and vectors"});
            continue;
        }
        order.push_back(&p);
    }
    // Larger members first; an array counts its whole registers.
    std::stable_sort(order.begin(), order.end(), [](const Parameter* a, const Parameter* b) {
        return words_of(*a) > words_of(*b);
    });

    std::vector<bool> used; // one flag per 4-byte word
    UniformLayout layout;
    for (const Parameter* p : order) {
        const uint32_t words = words_of(*p);
        const uint32_t align_words = alignment_of(*p) / 4;
        uint32_t w = 0;
        for (;; w += align_words) {
            if (!p->array_size && w / 4 != (w + words - 1) / 4)
                continue; // would straddle a 16-byte register
            bool free = true;
            for (uint32_t i = w; i < w + words; ++i)
                free = free && (i >= used.size() || !used[i]);
            if (free) break;
        }
        if (used.size() < w + words) used.resize(w + words, false);
        for (uint32_t i = w; i < w + words; ++i)
            used[i] = true;
        layout.members.push_back({p->name, p->type, w * 4, p->array_size});
    }
    std::sort(layout.members.begin(), layout.members.end(),
              [](const UniformSlot& a, const UniformSlot& b) { return a.offset < b.offset; });
    layout.size = static_cast<uint32_t>((used.size() * 4 + 15) / 16 * 16);
    return layout;
}

std::vector<uint8_t> pack_uniforms(const UniformLayout& layout,
                                   const std::vector<Parameter>& parameters,
                                   const std::map<std::string, std::vector<double>>& overrides,
                                   const std::optional<FrameCentre>& centre) {
    std::vector<uint8_t> bytes(layout.size, 0);
    const ParameterValues host = host_values(parameters, overrides, centre);
    for (const auto& slot : layout.members)
        for (const auto& p : parameters) {
            if (p.name != slot.name) continue;
            const std::vector<double>* values = &p.default_value;
            if (auto it = overrides.find(p.name);
                it != overrides.end() && it->second.size() == p.default_value.size())
                values = &it->second;
            if (auto it = host.find(p.name); it != host.end()) values = &it->second;
            // Element e of an array starts at offset + e * kArrayStride.
            const auto components = static_cast<size_t>(component_count(p.type));
            for (size_t i = 0; i < values->size(); ++i) {
                const float f = static_cast<float>((*values)[i]);
                const size_t at =
                    slot.offset + (i / components) * kArrayStride + 4 * (i % components);
                if (at + 4 <= bytes.size()) std::memcpy(bytes.data() + at, &f, 4);
            }
        }
    return bytes;
}

} // namespace watergen
