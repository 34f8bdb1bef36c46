#include "watergen/water/axis_registry.h"

#include <algorithm>

#include "axis_tables.h"
#include "watergen/water/surface.h"

namespace watergen {

namespace {

struct Registry {
    // Order is the order of a variant key. Seeds: 000 Toman, 001 Lombard, 002 Mihalik,
    // 003 IceFall, 004 sum of sines / Gerstner / Atlas (../shared/docs/water-models.md).
    // caustics came last, so every key before it reads as it did.
    std::vector<AxisInfo> axes = {fresnel_axis(),   extinction_axis(), specular_axis(),
                                  foam_axis(),      reflection_axis(), refraction_axis(),
                                  normals_axis(),   waves_axis(),      shore_axis(),
                                  precision_axis(), caustics_axis()};
    bool frozen = false;
};

Registry& registry() {
    static Registry r;
    return r;
}

AxisInfo* find_mutable_axis(std::vector<AxisInfo>& list, const std::string& name) {
    for (auto& a : list)
        if (a.name == name) return &a;
    return nullptr;
}

// Turns every_choice_but requirements into explicit lists, now that every choice is known.
void resolve_requirements(std::vector<AxisInfo>& list) {
    for (auto& axis : list)
        for (auto& choice : axis.choices)
            for (auto& r : choice.requirements) {
                if (!r.all_but) continue;
                std::vector<std::string> kept;
                if (const AxisInfo* other = find_mutable_axis(list, r.axis))
                    for (const auto& c : other->choices)
                        if (std::find(r.choices.begin(), r.choices.end(), c.name) ==
                            r.choices.end())
                            kept.push_back(c.name);
                r.choices = std::move(kept);
                r.all_but = false;
            }
}

} // namespace

ChoiceRequirement every_choice_but(const std::string& axis, std::vector<std::string> excluded,
                                   const std::string& why) {
    return {axis, std::move(excluded), why, true};
}

const std::vector<AxisInfo>& axes() {
    static const std::vector<AxisInfo> list = [] {
        Registry& r = registry();
        r.frozen = true;
        resolve_requirements(r.axes);
        return r.axes;
    }();
    return list;
}

const AxisInfo* find_axis(const std::string& name) {
    for (const auto& a : axes())
        if (a.name == name) return &a;
    return nullptr;
}

ChoiceInfo feature_choice(ChoiceInfo info, ChoiceNode node, std::function<void(Surface&)> compose) {
    info.node = std::move(node);
    info.compose = std::move(compose);
    return info;
}

const ChoiceInfo* find_choice(const AxisInfo& axis, const std::string& name) {
    for (const auto& c : axis.choices)
        if (c.name == name) return &c;
    return nullptr;
}

std::optional<std::string> register_choice(const std::string& axis, ChoiceInfo choice) {
    Registry& r = registry();
    const std::string what = "registering " + axis + "=" + choice.name + ": ";
    if (r.frozen)
        return what +
               "the axis registry is already in use (register before the first call to axes())";
    AxisInfo* a = find_mutable_axis(r.axes, axis);
    if (!a) return what + "unknown axis";
    for (const auto& c : a->choices)
        if (c.name == choice.name) return what + "the axis already has that choice";
    a->choices.push_back(std::move(choice));
    return std::nullopt;
}

void compose_choice(Surface& s, const std::string& axis, const std::string& choice) {
    const AxisInfo* a = find_axis(axis);
    const ChoiceInfo* c = a ? find_choice(*a, choice) : nullptr;
    if (!c) {
        s.g.error(axis + ": no node for choice '" + choice + "'");
        return;
    }
    if (c->compose) c->compose(s);
}

std::string axis_help(const AxisInfo& axis) {
    std::string help = "node on the " + axis.name + " axis (default " + axis.default_choice + "):";
    for (const auto& c : axis.choices) {
        help += "\n  " + c.name + (c.gold ? " (gold)" : "") + ": " + c.description;
        if (!c.approximates.empty()) help += "; approximates " + c.approximates;
        for (const auto& r : c.requirements) {
            std::string list;
            for (const auto& name : r.choices)
                list += (list.empty() ? "" : ", ") + name;
            help += "; needs " + r.axis + " in {" + list + "}";
        }
        if (!c.seed.empty()) help += " [seed " + c.seed + "]";
    }
    return help;
}

std::string axes_markdown_table() {
    std::string table = "| axis | choices |\n|---|---|\n";
    for (const auto& a : axes()) {
        std::string choices;
        for (const auto& c : a.choices) {
            std::string marks = c.seed;
            if (c.gold) marks += (marks.empty() ? "" : ", ") + std::string("gold");
            choices +=
                (choices.empty() ? "" : ", ") + c.name + (marks.empty() ? "" : " (" + marks + ")");
        }
        table += "| " + a.name + " | " + choices + " |\n";
    }
    return table;
}

} // namespace watergen
