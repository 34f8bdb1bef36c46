#include "watergen/variant.h"

#include <algorithm>

namespace watergen {

const std::vector<AxisInfo>& axes() {
    static const std::vector<AxisInfo> list = {
        {"fresnel",
         "schlick",
         {
             {"none", "", "constant reflectance", false},
             {"schlick", "000", "Schlick's approximation, R0 from the indices", false},
             {"exact", "", "unpolarised dielectric reflectance with total internal reflection", true},
         }},
        {"extinction",
         "absorb_scatter",
         {
             {"none", "", "refracted colour unchanged", false},
             {"absorb_scatter", "003", "exponential absorption plus scatter colour (IceFall)", false},
         }},
    };
    return list;
}

const AxisInfo* find_axis(const std::string& name) {
    for (const auto& a : axes())
        if (a.name == name) return &a;
    return nullptr;
}

namespace {

size_t axis_index(const std::string& name) {
    const auto& list = axes();
    for (size_t i = 0; i < list.size(); ++i)
        if (list[i].name == name) return i;
    return list.size();
}

std::string joined_names(const AxisInfo& a) {
    std::string s;
    for (const auto& c : a.choices) s += (s.empty() ? "" : ", ") + c.name;
    return s;
}

} // namespace

const std::string& Variant::choice(const std::string& axis) const {
    static const std::string none;
    const size_t i = axis_index(axis);
    return i < choices.size() ? choices[i] : none;
}

std::string Variant::key() const {
    std::string s;
    for (size_t i = 0; i < axes().size(); ++i)
        s += (i ? "," : "") + axes()[i].name + "=" + choices[i];
    return s;
}

std::string Variant::file_stem() const {
    std::string s;
    for (size_t i = 0; i < axes().size(); ++i)
        s += (i ? "_" : "") + axes()[i].name + "-" + choices[i];
    return s;
}

Variant default_variant() {
    Variant v;
    for (const auto& a : axes()) v.choices.push_back(a.default_choice);
    return v;
}

std::optional<std::string> set_choice(Variant& v, const std::string& axis, const std::string& choice) {
    const size_t i = axis_index(axis);
    if (i == axes().size()) {
        std::string names;
        for (const auto& a : axes()) names += (names.empty() ? "" : ", ") + a.name;
        return "unknown axis '" + axis + "' (axes: " + names + ")";
    }
    const AxisInfo& a = axes()[i];
    for (const auto& c : a.choices)
        if (c.name == choice) {
            v.choices[i] = choice;
            return std::nullopt;
        }
    return "unknown " + axis + " choice '" + choice + "' (choices: " + joined_names(a) + ")";
}

std::optional<Variant> parse_variant_key(const std::string& key, std::string* error) {
    Variant v = default_variant();
    size_t start = 0;
    while (start < key.size()) {
        size_t end = key.find(',', start);
        if (end == std::string::npos) end = key.size();
        const std::string item = key.substr(start, end - start);
        const size_t eq = item.find('=');
        if (eq == std::string::npos) {
            if (error) *error = "variant key item '" + item + "': expected axis=choice";
            return std::nullopt;
        }
        if (auto e = set_choice(v, item.substr(0, eq), item.substr(eq + 1))) {
            if (error) *error = *e;
            return std::nullopt;
        }
        start = end + 1;
    }
    return v;
}

std::vector<Variant> all_variants() {
    std::vector<Variant> out{Variant{}};
    for (const auto& a : axes()) {
        std::vector<Variant> next;
        for (const auto& partial : out)
            for (const auto& c : a.choices) {
                Variant v = partial;
                v.choices.push_back(c.name);
                next.push_back(std::move(v));
            }
        out = std::move(next);
    }
    std::sort(out.begin(), out.end(), [](const Variant& a, const Variant& b) { return a.key() < b.key(); });
    return out;
}

} // namespace watergen
