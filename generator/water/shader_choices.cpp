// Build modes and the choices one shader composes per axis (water_shader.h).
#include <algorithm>

#include "watergen/ir/core/text.h"
#include "watergen/water/axis_registry.h"
#include "watergen/water/water_shader.h"

namespace watergen {

namespace {

constexpr std::pair<BuildMode, const char*> kModes[] = {
    {BuildMode::Permutations, "permutations"},
    {BuildMode::Specialized, "specialized"},
    {BuildMode::Branching, "branching"},
};

size_t axis_position(const std::string& axis) {
    const auto& list = axes();
    for (size_t i = 0; i < list.size(); ++i)
        if (list[i].name == axis) return i;
    return list.size();
}

size_t choice_position(const std::string& axis, const std::string& choice) {
    const AxisInfo* a = find_axis(axis);
    for (size_t i = 0; a && i < a->choices.size(); ++i)
        if (a->choices[i].name == choice) return i;
    return SIZE_MAX;
}

} // namespace

const char* to_string(BuildMode m) {
    for (const auto& [mode, name] : kModes)
        if (mode == m) return name;
    return "?";
}

std::optional<BuildMode> parse_build_mode(const std::string& name) {
    for (const auto& [mode, n] : kModes)
        if (name == n) return mode;
    return std::nullopt;
}

std::string build_mode_names() {
    std::vector<std::string> names;
    for (const auto& m : kModes)
        names.push_back(m.second);
    return join(names);
}

std::string selector_parameter(const std::string& axis) {
    return "axis_" + axis;
}

bool permutation_only(const std::string& axis) {
    const AxisInfo* info = find_axis(axis);
    return info && info->permutation_only;
}

ShaderChoices ShaderChoices::of(const Variant& v) {
    ShaderChoices c;
    for (const auto& choice : v.choices)
        c.choices.push_back({choice});
    return c;
}

const std::vector<std::string>& ShaderChoices::offered(const std::string& axis) const {
    static const std::vector<std::string> none;
    const size_t i = axis_position(axis);
    return i < choices.size() ? choices[i] : none;
}

std::string ShaderChoices::key() const {
    std::vector<std::string> parts;
    for (size_t i = 0; i < axes().size() && i < choices.size(); ++i)
        if (spelled_in_key(axes()[i], choices[i]))
            parts.push_back(axes()[i].name + "=" + join(choices[i], "|"));
    return join(parts, ",");
}

std::string ShaderChoices::file_stem() const {
    std::vector<std::string> parts;
    for (size_t i = 0; i < axes().size() && i < choices.size(); ++i)
        if (spelled_in_key(axes()[i], choices[i]))
            parts.push_back(axes()[i].name + "-" + join(choices[i], "+"));
    return capped_file_stem(join(parts, "_"), key());
}

bool ShaderChoices::covers(const Variant& v) const {
    if (v.choices.size() != choices.size()) return false;
    for (size_t i = 0; i < choices.size(); ++i)
        if (std::find(choices[i].begin(), choices[i].end(), v.choices[i]) == choices[i].end())
            return false;
    return true;
}

std::vector<std::string> ShaderChoices::switched_axes() const {
    std::vector<std::string> out;
    for (size_t i = 0; i < axes().size() && i < choices.size(); ++i)
        if (choices[i].size() > 1) out.push_back(axes()[i].name);
    return out;
}

std::map<std::string, double> ShaderChoices::selector_values(const Variant& v) const {
    std::map<std::string, double> out;
    for (size_t i = 0; i < axes().size() && i < choices.size() && i < v.choices.size(); ++i) {
        if (choices[i].size() < 2) continue;
        const auto it = std::find(choices[i].begin(), choices[i].end(), v.choices[i]);
        out[selector_parameter(axes()[i].name)] = static_cast<double>(it - choices[i].begin());
    }
    return out;
}

Variant ShaderChoices::first_variant() const {
    Variant v = default_variant();
    for (size_t i = 0; i < v.choices.size() && i < choices.size(); ++i)
        if (!choices[i].empty()) v.choices[i] = choices[i].front();
    return v;
}

std::vector<ShaderChoices> shaders_for(const std::vector<Variant>& variants, BuildMode mode) {
    std::vector<ShaderChoices> out;
    if (mode == BuildMode::Permutations) {
        for (const Variant& v : variants)
            out.push_back(ShaderChoices::of(v));
        return out;
    }
    // One shader per combination of the permutation-only axes' choices, in order of appearance.
    std::map<std::string, size_t> group;
    for (const Variant& v : variants) {
        std::string fixed;
        for (size_t i = 0; i < axes().size(); ++i)
            if (permutation_only(axes()[i].name)) fixed += v.choices[i] + ",";
        auto [it, fresh] = group.emplace(fixed, out.size());
        if (fresh) out.push_back({mode, std::vector<std::vector<std::string>>(axes().size())});
        ShaderChoices& s = out[it->second];
        for (size_t i = 0; i < axes().size(); ++i)
            if (std::find(s.choices[i].begin(), s.choices[i].end(), v.choices[i]) ==
                s.choices[i].end())
                s.choices[i].push_back(v.choices[i]);
    }
    for (ShaderChoices& s : out) // registry order: a switch's cases do not depend on the list
        for (size_t i = 0; i < axes().size(); ++i)
            std::sort(s.choices[i].begin(), s.choices[i].end(),
                      [&](const std::string& a, const std::string& b) {
                          return choice_position(axes()[i].name, a) <
                                 choice_position(axes()[i].name, b);
                      });
    std::sort(out.begin(), out.end(),
              [](const ShaderChoices& a, const ShaderChoices& b) { return a.key() < b.key(); });
    return out;
}

} // namespace watergen
