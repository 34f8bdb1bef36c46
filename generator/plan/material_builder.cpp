// MaterialBuilder: the setters record; build() validates in a fixed order.
#include "watergen/plan/material.h"

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "watergen/ir/core/text.h"
#include "watergen/water/presets.h"

namespace watergen {

namespace {

std::vector<std::string> choice_names(const AxisInfo& a) {
    std::vector<std::string> names;
    for (const auto& c : a.choices)
        names.push_back(c.name);
    return names;
}

std::string axis_names() {
    std::vector<std::string> names;
    for (const auto& a : axes())
        names.push_back(a.name);
    return join(names);
}

size_t axis_index(const std::string& name) {
    for (size_t i = 0; i < axes().size(); ++i)
        if (axes()[i].name == name) return i;
    return axes().size();
}

bool has_choice(const AxisInfo& a, const std::string& choice) {
    for (const auto& c : a.choices)
        if (c.name == choice) return true;
    return false;
}

std::string unit_suffix(const Parameter& p) {
    return p.unit.empty() ? "" : " " + p.unit;
}

// The rule that rules `choice` of `axis` out: the first one broken with that choice fixed.
// *subject tells whether the rule is about that choice.
std::string why_unusable(const VariantSpace& space, size_t axis, const std::string& choice,
                         bool* subject) {
    VariantSpace probe = space;
    probe.choices[axis] = {choice};
    probe.rules.clear();
    std::string why;
    enumerate(probe, [&](const Variant& v) {
        if (!why.empty()) return;
        if (const Rule* r = find_broken_rule(space.rules, v)) {
            why = *broken_rule(space.rules, v);
            *subject = r->axis == axes()[axis].name && r->choice == choice;
        }
    });
    return why;
}

// The parameters `probes` declare, composed one by one; *error as for declared_parameters.
std::map<std::string, Parameter> declarations_of(const std::vector<Variant>& probes,
                                                 std::optional<Diagnostic>* error) {
    std::map<std::string, Parameter> declared;
    for (const Variant& v : probes) {
        const WaterShader s = build_water_shader(v, nullptr);
        // A mesh geometry's stages declare theirs too (the camera, the grid, the factors).
        std::vector<const Graph*> graphs = {&s.fragment};
        if (s.mesh)
            for (const Graph* stage : s.mesh->graphs())
                graphs.push_back(stage);
        for (const Graph* g : graphs)
            for (const Diagnostic& d : g->diagnostics())
                if (d.severity == Severity::Error && !error->has_value()) *error = d;
        for (const Graph* g : graphs)
            for (const Parameter& p : g->parameters()) {
                const auto [it, fresh] = declared.emplace(p.name, p);
                const Parameter& first = it->second;
                if (fresh || error->has_value() || first.author == p.author ||
                    same_definition(first, p))
                    continue;
                *error = Diagnostic{Severity::Error,
                                    p.defined_at.file,
                                    p.defined_at.line,
                                    0,
                                    p.origin,
                                    definition_clash("parameter", p.name, p.origin, p.defined_at,
                                                     first.origin, first.defined_at)};
            }
    }
    return declared;
}

// Parameters the offered nodes declare, found by composing one valid variant per offered choice.
// *error is the first mistake in a node's definition this finds, before anything is built: an
// error composing the IR (a project's node with a type error, at its registering file and
// line), or two authors' different definitions of one name (a project's node and watergen's,
// or two projects'), which would give one uniform two meanings across the material's variants.
std::map<std::string, Parameter> declared_parameters(const VariantSpace& space,
                                                     std::optional<Diagnostic>* error) {
    std::vector<std::vector<bool>> seen(axes().size());
    for (size_t i = 0; i < axes().size(); ++i)
        seen[i].assign(space.choices[i].size(), false);
    std::vector<Variant> probes;
    enumerate_indices(space, [&](const std::vector<size_t>& index) {
        bool fresh = false;
        for (size_t i = 0; i < index.size(); ++i)
            if (!seen[i][index[i]]) fresh = seen[i][index[i]] = true;
        if (!fresh) return;
        Variant v = default_variant();
        for (size_t i = 0; i < index.size(); ++i)
            v.choices[i] = space.choices[i][index[i]];
        probes.push_back(std::move(v));
    });
    return declarations_of(probes, error);
}

} // namespace

std::optional<Diagnostic> check_registered_nodes() {
    bool registered = false;
    for (const AxisInfo& a : axes())
        for (const ChoiceInfo& c : a.choices)
            registered |= !c.author.builtin();
    if (!registered) return std::nullopt;
    std::vector<Variant> probes;
    for (size_t i = 0; i < axes().size(); ++i)
        for (const ChoiceInfo& c : axes()[i].choices) {
            Variant v = default_variant();
            v.choices[i] = c.name;
            if (!check_constraints(v)) probes.push_back(std::move(v));
        }
    std::optional<Diagnostic> error;
    declarations_of(probes, &error);
    return error;
}

MaterialBuilder::MaterialBuilder(std::string name, SourceRef at)
    : name_(std::move(name)), name_at_(std::move(at)) {}

MaterialBuilder& MaterialBuilder::description(std::string text) {
    description_ = std::move(text);
    return *this;
}

MaterialBuilder& MaterialBuilder::offer(const std::string& axis,
                                        const std::vector<std::string>& choices, SourceRef at) {
    offers_.push_back({axis, choices, false, std::move(at)});
    return *this;
}

MaterialBuilder& MaterialBuilder::offer_all(const std::string& axis, SourceRef at) {
    offers_.push_back({axis, {}, true, std::move(at)});
    return *this;
}

MaterialBuilder& MaterialBuilder::requires_choice(const std::string& axis,
                                                  const std::string& choice,
                                                  const std::string& other_axis,
                                                  const std::vector<std::string>& other_choices,
                                                  std::string why, SourceRef at) {
    rules_.push_back({{Rule::Kind::Requires, axis, choice, other_axis, other_choices,
                       std::move(why), at.where()},
                      at});
    return *this;
}

MaterialBuilder& MaterialBuilder::excludes_choice(const std::string& axis,
                                                  const std::string& choice,
                                                  const std::string& other_axis,
                                                  const std::vector<std::string>& other_choices,
                                                  std::string why, SourceRef at) {
    rules_.push_back({{Rule::Kind::Excludes, axis, choice, other_axis, other_choices,
                       std::move(why), at.where()},
                      at});
    return *this;
}

MaterialBuilder& MaterialBuilder::preset(const std::string& name, SourceRef at) {
    preset_ = std::make_pair(name, std::move(at));
    return *this;
}

MaterialBuilder& MaterialBuilder::parameter(const std::string& name,
                                            const std::vector<double>& value, SourceRef at) {
    parameters_.push_back({name, value, std::nullopt, std::move(at)});
    return *this;
}

MaterialBuilder& MaterialBuilder::range(const std::string& name, double min, double max,
                                        SourceRef at) {
    parameters_.push_back({name, std::nullopt, std::make_pair(min, max), std::move(at)});
    return *this;
}

MaterialBuilder& MaterialBuilder::targets(const std::vector<std::string>& names, SourceRef at) {
    targets_ = std::make_pair(names, std::move(at));
    return *this;
}

// build() runs these steps in this order, each on what the ones before it settled, and stops at
// the first error: the name; the offers (axes and choices: the space's choices); the rules
// (names, and a subject on offer); every offered choice usable in some valid variant (no
// contradiction); the preset; the parameters (names, sizes, ranges); the values inside their
// ranges; the targets.
std::optional<Material> MaterialBuilder::build(Diagnostics& diagnostics) const {
    using Step = std::optional<Diagnostic> (MaterialBuilder::*)(Material&) const;
    static constexpr Step kSteps[] = {
        &MaterialBuilder::check_name,   &MaterialBuilder::check_offers,
        &MaterialBuilder::check_rules,  &MaterialBuilder::check_usable,
        &MaterialBuilder::check_preset, &MaterialBuilder::check_parameters,
        &MaterialBuilder::check_values, &MaterialBuilder::check_targets};
    Material m;
    m.name = name_;
    m.description = description_;
    m.file = name_at_.source ? name_at_.source->file() : "";
    for (Step step : kSteps)
        if (auto error = (this->*step)(m)) {
            diagnostics.push_back(std::move(*error));
            return std::nullopt;
        }
    return m;
}

std::optional<Diagnostic> MaterialBuilder::check_name(Material&) const {
    if (name_.empty() ||
        name_.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") != std::string::npos)
        return name_at_.error("material name '" + name_ +
                              "': expected lower-case letters, digits, '_' or '-'");
    return std::nullopt;
}

// The default of every axis, replaced by what the material offers.
std::optional<Diagnostic> MaterialBuilder::check_offers(Material& m) const {
    m.space.choices.resize(axes().size());
    for (size_t i = 0; i < axes().size(); ++i)
        m.space.choices[i] = {axes()[i].default_choice};
    std::vector<bool> offered(axes().size(), false);
    for (const Offer& o : offers_) {
        const size_t i = axis_index(o.axis);
        if (i == axes().size())
            return o.at.error("unknown axis '" + o.axis + "'; expected one of " + axis_names());
        if (offered[i]) return o.at.error("axis '" + o.axis + "' is offered twice");
        offered[i] = true;
        if (auto error = offered_choices(o, m.space.choices[i])) return error;
    }
    return std::nullopt;
}

// The choices of one offer, in documentation order whatever the order of the call: the space
// is canonical.
std::optional<Diagnostic> MaterialBuilder::offered_choices(const Offer& o,
                                                           std::vector<std::string>& choices) {
    const AxisInfo& a = axes()[axis_index(o.axis)];
    if (o.all) {
        choices = choice_names(a);
        return std::nullopt;
    }
    if (o.choices.empty())
        return o.at.error("axis '" + o.axis + "' offers no choice; expected at least one of " +
                          join(choice_names(a)));
    std::set<std::string> seen;
    for (size_t k = 0; k < o.choices.size(); ++k) {
        const std::string& c = o.choices[k];
        if (!has_choice(a, c))
            return o.at.child(k).error("unknown " + o.axis + " choice '" + c +
                                       "'; expected one of " + join(choice_names(a)));
        if (!seen.insert(c).second)
            return o.at.child(k).error(o.axis + " choice '" + c + "' is listed twice");
    }
    choices.clear();
    for (const auto& c : a.choices)
        if (seen.count(c.name)) choices.push_back(c.name);
    return std::nullopt;
}

// Names must exist, and a rule must be about a choice on offer.
std::optional<Diagnostic> MaterialBuilder::check_rules(Material& m) const {
    m.space.rules = builtin_rules();
    for (const RuleCall& r : rules_) {
        for (const std::string* axis : {&r.rule.axis, &r.rule.other_axis})
            if (axis_index(*axis) == axes().size())
                return r.at.error("unknown axis '" + *axis + "'; expected one of " + axis_names());
        const AxisInfo& a = axes()[axis_index(r.rule.axis)];
        const AxisInfo& b = axes()[axis_index(r.rule.other_axis)];
        if (!has_choice(a, r.rule.choice))
            return r.at.error("unknown " + a.name + " choice '" + r.rule.choice +
                              "'; expected one of " + join(choice_names(a)));
        if (r.rule.axis == r.rule.other_axis)
            return r.at.error("a rule relates two different axes; got " + a.name + " twice");
        const auto& on_offer = m.space.choices[axis_index(r.rule.axis)];
        if (std::find(on_offer.begin(), on_offer.end(), r.rule.choice) == on_offer.end())
            return r.at.error("rule about " + a.name + "=" + r.rule.choice +
                              ", which the material does not offer (offered: " + join(on_offer) +
                              ")");
        if (r.rule.other_choices.empty())
            return r.at.error("rule lists no " + b.name + " choice; expected at least one of " +
                              join(choice_names(b)));
        for (const auto& c : r.rule.other_choices)
            if (!has_choice(b, c))
                return r.at.error("unknown " + b.name + " choice '" + c + "'; expected one of " +
                                  join(choice_names(b)));
        m.space.rules.push_back(r.rule);
    }
    return std::nullopt;
}

// Every offered choice must be usable in at least one valid variant. Reports the unusable
// choice that a broken rule is about (its subject), else the first unusable one.
std::optional<Diagnostic> MaterialBuilder::check_usable(Material& m) const {
    std::vector<std::vector<bool>> used(axes().size());
    for (size_t i = 0; i < axes().size(); ++i)
        used[i].assign(m.space.choices[i].size(), false);
    size_t count = 0;
    enumerate_indices(m.space, [&](const std::vector<size_t>& index) {
        ++count;
        for (size_t i = 0; i < index.size(); ++i)
            used[i][index[i]] = true;
    });
    std::optional<Diagnostic> first_unusable;
    for (size_t i = 0; i < axes().size(); ++i)
        for (size_t k = 0; k < m.space.choices[i].size(); ++k) {
            const std::string& c = m.space.choices[i][k];
            if (used[i][k]) continue;
            bool subject = false;
            const std::string why = why_unusable(m.space, i, c, &subject);
            Diagnostic d =
                offered_at(i, c).error("contradictory constraints: " + axes()[i].name + "=" + c +
                                       " is offered but no valid variant can use it: " + why);
            if (subject) return d;
            if (!first_unusable) first_unusable = d;
        }
    if (first_unusable) return first_unusable;
    if (count == 0)
        return name_at_.error("contradictory constraints: the material has no valid variant");
    return std::nullopt;
}

// Where the offer of `choice` on axis `axis` was made (nothing for an axis never offered).
SourceRef MaterialBuilder::offered_at(size_t axis, const std::string& choice) const {
    for (const Offer& o : offers_) {
        if (o.axis != axes()[axis].name) continue;
        if (o.all) return o.at;
        const auto k = std::find(o.choices.begin(), o.choices.end(), choice);
        return o.at.child(static_cast<size_t>(k - o.choices.begin()));
    }
    return {};
}

std::optional<Diagnostic> MaterialBuilder::check_preset(Material& m) const {
    if (!preset_) return std::nullopt;
    if (!find_preset(preset_->first))
        return preset_->second.error("unknown preset '" + preset_->first + "'; expected one of " +
                                     preset_names());
    m.preset = preset_->first;
    return std::nullopt;
}

// Names against the parameters the offered nodes declare; sizes; ranges inside the node's.
std::optional<Diagnostic> MaterialBuilder::check_parameters(Material& m) const {
    std::optional<Diagnostic> error;
    m.declared = declared_parameters(m.space, &error);
    if (error) return error;
    std::vector<std::string> declared_names;
    for (const auto& [n, p] : m.declared)
        declared_names.push_back(n);
    for (const ParameterCall& call : parameters_) {
        auto it = m.declared.find(call.name);
        if (it == m.declared.end())
            return call.at.error("unknown parameter '" + call.name + "'; the offered nodes read " +
                                 join(declared_names));
        ParameterSetting& s = m.parameters[call.name];
        if (s.where.empty()) s.where = call.at.where();
        if (auto error = apply_setting(call, it->second, s)) return error;
    }
    return std::nullopt;
}

std::optional<Diagnostic> MaterialBuilder::apply_setting(const ParameterCall& call,
                                                         const Parameter& p, ParameterSetting& s) {
    if (call.value) {
        if (s.value) return call.at.error("parameter '" + call.name + "' is given a value twice");
        const size_t n = value_count(p); // every element of an array, as a scene's "fixed"
        if (call.value->size() != n)
            return call.at.error(fmt::format(
                "parameter '{}' is a {}{}: expected {} number{}, got {}", call.name,
                type_name(p.type), p.array_size ? fmt::format("[{}]", p.array_size) : "", n,
                n == 1 ? "" : "s", call.value->size()));
        if (p.flag)
            for (double x : *call.value)
                if (x != 0 && x != 1)
                    return call.at.error("parameter '" + call.name +
                                         "' is a switch: expected 0 "
                                         "or 1, got " +
                                         spell_number(x));
        s.value = *call.value;
    }
    if (call.range) {
        if (s.min) return call.at.error("parameter '" + call.name + "' is given a range twice");
        const auto [lo, hi] = *call.range;
        if (lo > hi)
            return call.at.error("range of '" + call.name + "': min " + spell_number(lo) +
                                 " is above max " + spell_number(hi) + "; expected min <= max");
        if (lo < p.min || hi > p.max)
            return call.at.error(
                "range of '" + call.name + "' [" + spell_number(lo) + ", " + spell_number(hi) +
                "] leaves the range its node declares; expected within [" + spell_number(p.min) +
                ", " + spell_number(p.max) + "]" + unit_suffix(p));
        s.min = lo;
        s.max = hi;
    }
    return std::nullopt;
}

// Values inside the (narrowed) ranges, checked once both are known.
std::optional<Diagnostic> MaterialBuilder::check_values(Material& m) const {
    for (const ParameterCall& call : parameters_) {
        if (!call.value) continue;
        const auto [lo, hi] = m.range(call.name);
        for (size_t k = 0; k < call.value->size(); ++k) {
            const double x = (*call.value)[k];
            if (x >= lo && x <= hi) continue;
            const SourceRef at = call.value->size() > 1 ? call.at.child(k) : call.at;
            return at.error("value " + spell_number(x) + " of '" + call.name +
                            "' is out of range; expected a value in [" + spell_number(lo) + ", " +
                            spell_number(hi) + "]" + unit_suffix(m.declared[call.name]));
        }
    }
    return std::nullopt;
}

std::optional<Diagnostic> MaterialBuilder::check_targets(Material& m) const {
    if (!targets_) {
        m.targets = all_targets();
        return std::nullopt;
    }
    const auto& [names, at] = *targets_;
    if (names.empty()) return at.error("no targets; expected at least one of " + target_names());
    std::set<Target> chosen;
    for (size_t k = 0; k < names.size(); ++k) {
        const auto t = parse_target(names[k]);
        if (!t)
            return at.child(k).error("unknown target '" + names[k] + "'; expected one of " +
                                     target_names());
        if (!chosen.insert(*t).second)
            return at.child(k).error("target '" + names[k] + "' is listed twice");
    }
    for (Target t : all_targets())
        if (chosen.count(t)) m.targets.push_back(t);
    return std::nullopt;
}

} // namespace watergen
