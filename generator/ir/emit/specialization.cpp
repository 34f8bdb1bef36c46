#include "watergen/ir/emit/specialization.h"

namespace watergen {

bool is_specialized(const Parameter& p, const std::set<std::string>& names) {
    return p.specialization || names.count(p.name) > 0;
}

std::vector<SpecializationSlot> specialization_slots(const std::vector<Parameter>& parameters,
                                                     Diagnostics& diagnostics) {
    std::vector<SpecializationSlot> slots;
    for (const auto& p : parameters) {
        if (!p.specialization) continue;
        if (p.array_size) {
            // A constant per element would do, but the loop reading the array indexes it.
            diagnostics.push_back({Severity::Error, "", 0, 0, p.origin,
                                   "parameter '" + p.name +
                                       "' is an array; arrays cannot be specialization constants"});
            continue;
        }
        if (!is_float_numeric(p.type)) {
            diagnostics.push_back({Severity::Error, "", 0, 0, p.origin,
                                   "parameter '" + p.name + "' has type " + type_name(p.type) +
                                       "; specialization constants hold float scalars and "
                                       "vectors"});
            continue;
        }
        const int components = component_count(p.type);
        for (int c = 0; c < components && c < static_cast<int>(p.default_value.size()); ++c) {
            SpecializationSlot s;
            s.id = static_cast<uint32_t>(slots.size());
            s.name = components == 1 ? p.name : p.name + "_" + "xyzw"[c];
            s.parameter = p.name;
            s.component = static_cast<uint32_t>(c);
            s.default_value = p.default_value[c];
            s.min = p.min;
            s.max = p.max;
            slots.push_back(std::move(s));
        }
    }
    return slots;
}

void check_specialization_names(const std::vector<Parameter>& parameters,
                                const std::set<std::string>& names, Diagnostics& diagnostics) {
    for (const auto& name : names) {
        bool declared = false;
        for (const auto& p : parameters)
            declared = declared || p.name == name;
        if (!declared)
            diagnostics.push_back(
                {Severity::Error, "", 0, 0, "",
                 "specialization constant '" + name + "' names no parameter of the shader"});
    }
}

std::map<uint32_t, float>
specialization_values(const std::vector<SpecializationSlot>& slots,
                      const std::map<std::string, std::vector<double>>& overrides) {
    std::map<uint32_t, float> values;
    for (const auto& s : slots) {
        double v = s.default_value;
        if (auto it = overrides.find(s.parameter); it != overrides.end()) {
            // Same rule as pack_uniforms: an override of another size is ignored.
            size_t components = 0;
            for (const auto& other : slots)
                components += other.parameter == s.parameter ? 1 : 0;
            if (it->second.size() == components) v = it->second[s.component];
        }
        values[s.id] = static_cast<float>(v);
    }
    return values;
}

void add_specialization_ranges(Reflection& reflection,
                               const std::vector<SpecializationSlot>& slots) {
    for (auto& c : reflection.specialization_constants)
        for (const auto& s : slots)
            if (s.id == c.id && s.name == c.name) {
                c.min = s.min;
                c.max = s.max;
            }
}

} // namespace watergen
