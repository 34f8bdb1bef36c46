#include "watergen/water/axis_registry.h"

#include <algorithm>

#include "axis_tables.h"
#include "watergen/ir/core/identifier.h"
#include "watergen/water/surface.h"

namespace watergen {

namespace {

struct Registry {
    // Order is the order of a variant key. Seeds: 000 Toman, 001 Lombard, 002 Mihalik,
    // 003 IceFall, 004 sum of sines / Gerstner / Atlas (../shared/docs/water-models.md).
    // caustics, scene_input and geometry came last, in that order.
    std::vector<AxisInfo> axes = {
        fresnel_axis(),    extinction_axis(),  specular_axis(), foam_axis(),  reflection_axis(),
        refraction_axis(), normals_axis(),     waves_axis(),    shore_axis(), precision_axis(),
        caustics_axis(),   scene_input_axis(), geometry_axis()};
    // The order water_shader.cpp composes watergen's axes in: the surface first (waves,
    // normals), then what the view ray sees through and off it, then what lies on top.
    // Precision composes nothing (it scopes the shading); geometry and scene_input compose in
    // the skeleton, before the view ray; registered axes join on freezing.
    std::vector<std::string> composition = {"waves",      "normals",    "refraction", "caustics",
                                            "extinction", "reflection", "fresnel",    "specular",
                                            "foam",       "shore"};
    Diagnostics errors;
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

namespace {

// Places each registered axis right after its compose_after, in registration order; an axis
// placed after another registered one waits for it (registration order across files is the
// static initialisation order, which C++ leaves open).
void place_registered_axes(Registry& r) {
    std::vector<const AxisInfo*> pending;
    for (const auto& a : r.axes)
        if (!a.author.builtin()) pending.push_back(&a);
    for (bool placed = true; placed && !pending.empty();) {
        placed = false;
        for (auto it = pending.begin(); it != pending.end(); ++it) {
            auto after =
                std::find(r.composition.begin(), r.composition.end(), (*it)->compose_after);
            if (after == r.composition.end()) continue;
            // After the anchor and every axis placed after it before this one.
            auto at = after + 1;
            while (at != r.composition.end()) {
                const AxisInfo* other = find_mutable_axis(r.axes, *at);
                if (!other || other->author.builtin()) break;
                ++at;
            }
            r.composition.insert(at, (*it)->name);
            pending.erase(it);
            placed = true;
            break;
        }
    }
    for (const AxisInfo* a : pending) {
        std::string anchors;
        for (const auto& name : r.composition)
            anchors += (anchors.empty() ? "" : ", ") + name;
        r.errors.push_back({Severity::Error, a->author.file, a->author.line, 0, "",
                            "registering axis " + a->name + ": compose_after '" + a->compose_after +
                                "' is not a composed axis (one of " + anchors + ")"});
    }
}

Registry& frozen_registry() {
    static const bool frozen = [] {
        Registry& r = registry();
        r.frozen = true;
        resolve_requirements(r.axes);
        place_registered_axes(r);
        return true;
    }();
    (void)frozen;
    return registry();
}

// Why `name` cannot name an axis or a choice: it appears in keys, file names and --options.
std::optional<std::string> name_problem(const std::string& name) {
    if (name.empty() || name.front() < 'a' || name.front() > 'z')
        return "'" + name + "' must start with a lower-case letter";
    for (char c : name)
        if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_'))
            return "'" + name + "' may hold only a-z, 0-9 and '_'";
    return std::nullopt;
}

// Records a failed registration at its call and returns the message.
std::optional<std::string> refuse(Registry& r, const SourceLocation& where, std::string message) {
    r.errors.push_back({Severity::Error, where.file, where.line, 0, "", message});
    return message;
}

} // namespace

const std::vector<AxisInfo>& axes() {
    return frozen_registry().axes;
}

bool spelled_in_key(const AxisInfo& axis, const std::string& choice) {
    return axis.keyed_at_default || choice != axis.default_choice;
}

bool spelled_in_key(const AxisInfo& axis, const std::vector<std::string>& choices) {
    return choices.size() != 1 || spelled_in_key(axis, choices.front());
}

const std::vector<std::string>& composition_order() {
    return frozen_registry().composition;
}

const Diagnostics& registration_errors() {
    return frozen_registry().errors;
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

std::optional<std::string> register_choice(const std::string& axis, ChoiceInfo choice,
                                           SourceLocation where) {
    Registry& r = registry();
    const std::string what = "registering " + axis + "=" + choice.name + ": ";
    if (r.frozen)
        return refuse(r, where,
                      what + "the axis registry is already in use (register before the first "
                             "call to axes(), e.g. with WATERGEN_REGISTER_NODES)");
    if (auto problem = name_problem(choice.name)) return refuse(r, where, what + *problem);
    AxisInfo* a = find_mutable_axis(r.axes, axis);
    if (!a) return refuse(r, where, what + "unknown axis");
    for (const auto& c : a->choices)
        if (c.name == choice.name)
            return refuse(r, where,
                          what + "the axis already has that choice (" +
                              (c.author.builtin() ? std::string("watergen's own")
                                                  : "registered at " + c.author.label()) +
                              ")");
    choice.author = {where.file, where.line};
    a->choices.push_back(std::move(choice));
    return std::nullopt;
}

std::optional<std::string> register_axis(AxisInfo axis, SourceLocation where) {
    Registry& r = registry();
    const std::string what = "registering axis " + axis.name + ": ";
    if (r.frozen)
        return refuse(r, where,
                      what + "the axis registry is already in use (register before the first "
                             "call to axes(), e.g. with WATERGEN_REGISTER_NODES)");
    if (auto problem = name_problem(axis.name)) return refuse(r, where, what + *problem);
    if (const AxisInfo* other = find_mutable_axis(r.axes, axis.name))
        return refuse(r, where,
                      what + "the name is taken (" +
                          (other->author.builtin() ? std::string("a watergen axis")
                                                   : "registered at " + other->author.label()) +
                          ")");
    if (axis.choices.empty()) return refuse(r, where, what + "no choices");
    if (axis.compose_after.empty())
        return refuse(r, where, what + "compose_after is empty (name the axis it follows)");
    const Author author{where.file, where.line};
    for (size_t i = 0; i < axis.choices.size(); ++i) {
        if (auto problem = name_problem(axis.choices[i].name))
            return refuse(r, where, what + "choice " + *problem);
        for (size_t j = 0; j < i; ++j)
            if (axis.choices[j].name == axis.choices[i].name)
                return refuse(r, where, what + "choice '" + axis.choices[i].name + "' twice");
        axis.choices[i].author = author;
    }
    if (!find_choice(axis, axis.default_choice))
        return refuse(r, where,
                      what + "default choice '" + axis.default_choice +
                          "' is not one of its "
                          "choices");
    axis.author = author;
    r.axes.push_back(std::move(axis));
    return std::nullopt;
}

void compose_choice(Surface& s, const std::string& axis, const std::string& choice) {
    const AxisInfo* a = find_axis(axis);
    const ChoiceInfo* c = a ? find_choice(*a, choice) : nullptr;
    if (!c) {
        s.g.error(axis + ": no node for choice '" + choice + "'");
        return;
    }
    if (!c->compose) return;
    if (c->author.builtin()) {
        c->compose(s);
        return;
    }
    // A project's choice: what it declares is its own, and its errors name its file and line.
    AuthorScope author(s.g, c->author);
    OriginScope origin(s.g, axis + "." + choice);
    c->compose(s);
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
