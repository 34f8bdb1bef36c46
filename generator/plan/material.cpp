#include "watergen/plan/material.h"

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "watergen/water/presets.h"

namespace watergen {

namespace {

std::string join(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

std::vector<std::string> choice_names(const AxisInfo& a) {
    std::vector<std::string> names;
    for (const auto& c : a.choices) names.push_back(c.name);
    return names;
}

std::string axis_names() {
    std::vector<std::string> names;
    for (const auto& a : axes()) names.push_back(a.name);
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

std::string spell_number(double v) { return fmt::format("{:g}", v); }

// A copy of `g` whose parameter declarations carry `params` (same nodes, same ids).
Graph with_parameters(const Graph& g, const std::vector<Parameter>& params) {
    Graph out;
    for (const Parameter& p : params) out.declare_parameter(p);
    for (const auto& t : g.textures()) out.declare_texture(t);
    for (uint32_t id = 0; id < g.size(); ++id) out.add(g.node(id));
    for (const auto& o : g.outputs()) out.set_output(o.name, o.node);
    for (const auto& b : g.bindings()) out.bind(b.quantity, b.node); // same ids: the scene facts still apply
    return out;
}

} // namespace

const std::vector<Target>& all_targets() {
    static const std::vector<Target> list = {Target::Glsl, Target::Hlsl, Target::Spirv, Target::Glsl330,
                                             Target::Essl300, Target::Msl, Target::Reflection};
    return list;
}

const char* to_string(Target t) {
    switch (t) {
    case Target::Glsl: return "glsl";
    case Target::Hlsl: return "hlsl";
    case Target::Spirv: return "spirv";
    case Target::Glsl330: return "glsl330";
    case Target::Essl300: return "essl300";
    case Target::Msl: return "msl";
    case Target::Reflection: return "reflection";
    }
    return "?";
}

std::optional<Target> parse_target(const std::string& name) {
    for (Target t : all_targets())
        if (name == to_string(t)) return t;
    return std::nullopt;
}

std::string target_names() {
    std::vector<std::string> names;
    for (Target t : all_targets()) names.push_back(to_string(t));
    return join(names);
}

std::string SourceRef::where() const {
    if (!source) return "";
    return source->where(pointer) + " " + (pointer.empty() ? "/" : pointer);
}

Diagnostic SourceRef::error(const std::string& what) const {
    if (source) return source->error(pointer, what);
    return Diagnostic{Severity::Error, "", 0, 0, "", what};
}

// ---------------------------------------------------------------------------------------
// Material

std::pair<double, double> Material::range(const std::string& parameter) const {
    double lo = 0.0, hi = 0.0;
    if (auto it = declared.find(parameter); it != declared.end()) {
        lo = it->second.min;
        hi = it->second.max;
    }
    if (auto it = parameters.find(parameter); it != parameters.end()) {
        if (it->second.min) lo = *it->second.min;
        if (it->second.max) hi = *it->second.max;
    }
    return {lo, hi};
}

WaterShader Material::compose(const Variant& v) const {
    WaterShader shader = build_water_shader(v, preset.empty() ? nullptr : find_preset(preset));
    if (has_errors(shader.fragment.diagnostics())) return shader;
    std::vector<Parameter> params = shader.fragment.parameters();
    for (Parameter& p : params) {
        auto it = parameters.find(p.name);
        if (it == parameters.end()) continue;
        if (it->second.value) p.default_value = *it->second.value;
        if (it->second.min) p.min = *it->second.min;
        if (it->second.max) p.max = *it->second.max;
    }
    shader.fragment = with_parameters(shader.fragment, params);
    return shader;
}

// ---------------------------------------------------------------------------------------
// Builder: records calls; build() validates them in a fixed order.

MaterialBuilder::MaterialBuilder(std::string name, SourceRef at) : name_(std::move(name)), name_at_(std::move(at)) {}

MaterialBuilder& MaterialBuilder::description(std::string text) {
    description_ = std::move(text);
    return *this;
}

MaterialBuilder& MaterialBuilder::offer(const std::string& axis, const std::vector<std::string>& choices, SourceRef at) {
    offers_.push_back({axis, choices, false, std::move(at)});
    return *this;
}

MaterialBuilder& MaterialBuilder::offer_all(const std::string& axis, SourceRef at) {
    offers_.push_back({axis, {}, true, std::move(at)});
    return *this;
}

MaterialBuilder& MaterialBuilder::requires_choice(const std::string& axis, const std::string& choice,
                                                  const std::string& other_axis,
                                                  const std::vector<std::string>& other_choices, std::string why,
                                                  SourceRef at) {
    rules_.push_back({{Rule::Kind::Requires, axis, choice, other_axis, other_choices, std::move(why), at.where()}, at});
    return *this;
}

MaterialBuilder& MaterialBuilder::excludes_choice(const std::string& axis, const std::string& choice,
                                                  const std::string& other_axis,
                                                  const std::vector<std::string>& other_choices, std::string why,
                                                  SourceRef at) {
    rules_.push_back({{Rule::Kind::Excludes, axis, choice, other_axis, other_choices, std::move(why), at.where()}, at});
    return *this;
}

MaterialBuilder& MaterialBuilder::preset(const std::string& name, SourceRef at) {
    preset_ = std::make_pair(name, std::move(at));
    return *this;
}

MaterialBuilder& MaterialBuilder::parameter(const std::string& name, const std::vector<double>& value, SourceRef at) {
    parameters_.push_back({name, value, std::nullopt, std::move(at)});
    return *this;
}

MaterialBuilder& MaterialBuilder::range(const std::string& name, double min, double max, SourceRef at) {
    parameters_.push_back({name, std::nullopt, std::make_pair(min, max), std::move(at)});
    return *this;
}

MaterialBuilder& MaterialBuilder::targets(const std::vector<std::string>& names, SourceRef at) {
    targets_ = std::make_pair(names, std::move(at));
    return *this;
}

std::optional<Material> MaterialBuilder::build(Diagnostics& diagnostics) const {
    auto fail = [&](Diagnostic d) -> std::optional<Material> {
        diagnostics.push_back(std::move(d));
        return std::nullopt;
    };
    Material m;
    m.name = name_;
    m.description = description_;
    m.file = name_at_.source ? name_at_.source->file() : "";
    if (name_.empty() || name_.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") != std::string::npos)
        return fail(name_at_.error("material name '" + name_ + "': expected lower-case letters, digits, '_' or '-'"));

    // Choices: the default of every axis, replaced by what the material offers.
    m.space.choices.resize(axes().size());
    for (size_t i = 0; i < axes().size(); ++i) m.space.choices[i] = {axes()[i].default_choice};
    std::vector<SourceRef> choice_at(axes().size());
    std::vector<bool> offered(axes().size(), false), offered_all(axes().size(), false);
    std::vector<std::map<std::string, size_t>> index_in_call(axes().size()); // choice -> element of its offer
    auto offers_all = [&](size_t i) { return bool(offered_all[i]); };
    for (const Offer& o : offers_) {
        const size_t i = axis_index(o.axis);
        if (i == axes().size()) return fail(o.at.error("unknown axis '" + o.axis + "'; expected one of " + axis_names()));
        const AxisInfo& a = axes()[i];
        if (offered[i]) return fail(o.at.error("axis '" + o.axis + "' is offered twice"));
        offered[i] = true;
        choice_at[i] = o.at;
        if (o.all) {
            offered_all[i] = true;
            m.space.choices[i] = choice_names(a);
            continue;
        }
        if (o.choices.empty())
            return fail(o.at.error("axis '" + o.axis + "' offers no choice; expected at least one of " + join(choice_names(a))));
        std::set<std::string> seen;
        for (size_t k = 0; k < o.choices.size(); ++k) {
            const std::string& c = o.choices[k];
            if (!has_choice(a, c))
                return fail(o.at.child(k).error("unknown " + o.axis + " choice '" + c + "'; expected one of " + join(choice_names(a))));
            if (!seen.insert(c).second) return fail(o.at.child(k).error(o.axis + " choice '" + c + "' is listed twice"));
            index_in_call[i][c] = k;
        }
        // Documentation order, whatever the order of the call: the space is canonical.
        m.space.choices[i].clear();
        for (const auto& c : a.choices)
            if (seen.count(c.name)) m.space.choices[i].push_back(c.name);
    }

    // Rules: names must exist, and the rule must be about a choice on offer.
    m.space.rules = builtin_rules();
    for (const RuleCall& r : rules_) {
        for (const std::string* axis : {&r.rule.axis, &r.rule.other_axis})
            if (axis_index(*axis) == axes().size())
                return fail(r.at.error("unknown axis '" + *axis + "'; expected one of " + axis_names()));
        const AxisInfo& a = axes()[axis_index(r.rule.axis)];
        const AxisInfo& b = axes()[axis_index(r.rule.other_axis)];
        if (!has_choice(a, r.rule.choice))
            return fail(r.at.error("unknown " + a.name + " choice '" + r.rule.choice + "'; expected one of " + join(choice_names(a))));
        if (r.rule.axis == r.rule.other_axis)
            return fail(r.at.error("a rule relates two different axes; got " + a.name + " twice"));
        const auto& on_offer = m.space.choices[axis_index(r.rule.axis)];
        if (std::find(on_offer.begin(), on_offer.end(), r.rule.choice) == on_offer.end())
            return fail(r.at.error("rule about " + a.name + "=" + r.rule.choice + ", which the material does not offer (offered: " +
                                   join(on_offer) + ")"));
        if (r.rule.other_choices.empty())
            return fail(r.at.error("rule lists no " + b.name + " choice; expected at least one of " + join(choice_names(b))));
        for (const auto& c : r.rule.other_choices)
            if (!has_choice(b, c))
                return fail(r.at.error("unknown " + b.name + " choice '" + c + "'; expected one of " + join(choice_names(b))));
        m.space.rules.push_back(r.rule);
    }

    // Contradictions: every offered choice must be usable in at least one valid variant.
    std::vector<std::set<std::string>> used(axes().size());
    size_t count = 0;
    enumerate(m.space, [&](const Variant& v) {
        ++count;
        for (size_t i = 0; i < axes().size(); ++i) used[i].insert(v.choices[i]);
    });
    // Report the unusable choice that a broken rule is about (its subject), else the first.
    std::optional<Diagnostic> first_unusable;
    for (size_t i = 0; i < axes().size(); ++i)
        for (size_t k = 0; k < m.space.choices[i].size(); ++k) {
            const std::string& c = m.space.choices[i][k];
            if (used[i].count(c)) continue;
            // Name the rule that rules it out: the first one broken with this choice fixed.
            VariantSpace probe = m.space;
            probe.choices[i] = {c};
            probe.rules.clear();
            std::string why;
            bool subject = false;
            enumerate(probe, [&](const Variant& v) {
                if (!why.empty()) return;
                if (const Rule* r = find_broken_rule(m.space.rules, v)) {
                    why = *broken_rule(m.space.rules, v);
                    subject = r->axis == axes()[i].name && r->choice == c;
                }
            });
            const SourceRef at = choice_at[i].source ? (offers_all(i) ? choice_at[i] : choice_at[i].child(index_in_call[i][c])) : SourceRef{};
            Diagnostic d = at.error("contradictory constraints: " + axes()[i].name + "=" + c +
                                    " is offered but no valid variant can use it: " + why);
            if (subject) return fail(d);
            if (!first_unusable) first_unusable = d;
        }
    if (first_unusable) return fail(*first_unusable);
    if (count == 0) return fail(name_at_.error("contradictory constraints: the material has no valid variant"));

    if (preset_) {
        if (!find_preset(preset_->first))
            return fail(preset_->second.error("unknown preset '" + preset_->first + "'; expected one of " + preset_names()));
        m.preset = preset_->first;
    }

    // Parameters the offered nodes declare: compose one valid variant per offered choice.
    {
        std::vector<std::set<std::string>> pending(axes().size());
        for (size_t i = 0; i < axes().size(); ++i) pending[i] = {m.space.choices[i].begin(), m.space.choices[i].end()};
        std::vector<Variant> probes;
        enumerate(m.space, [&](const Variant& v) {
            bool fresh = false;
            for (size_t i = 0; i < axes().size(); ++i) fresh = pending[i].erase(v.choices[i]) > 0 || fresh;
            if (fresh) probes.push_back(v);
        });
        for (const Variant& v : probes) {
            const WaterShader s = build_water_shader(v, nullptr);
            for (const Parameter& p : s.fragment.parameters()) m.declared.emplace(p.name, p);
        }
    }
    std::vector<std::string> declared_names;
    for (const auto& [n, p] : m.declared) declared_names.push_back(n);
    for (const ParameterCall& call : parameters_) {
        auto it = m.declared.find(call.name);
        if (it == m.declared.end())
            return fail(call.at.error("unknown parameter '" + call.name + "'; the offered nodes read " + join(declared_names)));
        const Parameter& p = it->second;
        ParameterSetting& s = m.parameters[call.name];
        if (s.where.empty()) s.where = call.at.where();
        const std::string unit = p.unit.empty() ? "" : " " + p.unit;
        if (call.value) {
            if (s.value) return fail(call.at.error("parameter '" + call.name + "' is given a value twice"));
            const size_t n = static_cast<size_t>(component_count(p.type));
            if (call.value->size() != n)
                return fail(call.at.error(fmt::format("parameter '{}' is a {}: expected {} number{}, got {}", call.name,
                                                      type_name(p.type), n, n == 1 ? "" : "s", call.value->size())));
            s.value = *call.value;
        }
        if (call.range) {
            if (s.min) return fail(call.at.error("parameter '" + call.name + "' is given a range twice"));
            const auto [lo, hi] = *call.range;
            if (lo > hi)
                return fail(call.at.error("range of '" + call.name + "': min " + spell_number(lo) + " is above max " +
                                          spell_number(hi) + "; expected min <= max"));
            if (lo < p.min || hi > p.max)
                return fail(call.at.error("range of '" + call.name + "' [" + spell_number(lo) + ", " + spell_number(hi) +
                                          "] leaves the range its node declares; expected within [" + spell_number(p.min) +
                                          ", " + spell_number(p.max) + "]" + unit));
            s.min = lo;
            s.max = hi;
        }
    }
    // Values inside the (narrowed) ranges, checked once both are known.
    for (const ParameterCall& call : parameters_) {
        if (!call.value) continue;
        const auto [lo, hi] = m.range(call.name);
        for (size_t k = 0; k < call.value->size(); ++k) {
            const double x = (*call.value)[k];
            if (x < lo || x > hi) {
                const std::string unit = m.declared[call.name].unit.empty() ? "" : " " + m.declared[call.name].unit;
                const SourceRef at = call.value->size() > 1 ? call.at.child(k) : call.at;
                return fail(at.error("value " + spell_number(x) + " of '" + call.name + "' is out of range; expected a value in [" +
                                     spell_number(lo) + ", " + spell_number(hi) + "]" + unit));
            }
        }
    }

    if (targets_) {
        const auto& [names, at] = *targets_;
        if (names.empty()) return fail(at.error("no targets; expected at least one of " + target_names()));
        std::set<Target> chosen;
        for (size_t k = 0; k < names.size(); ++k) {
            const auto t = parse_target(names[k]);
            if (!t) return fail(at.child(k).error("unknown target '" + names[k] + "'; expected one of " + target_names()));
            if (!chosen.insert(*t).second) return fail(at.child(k).error("target '" + names[k] + "' is listed twice"));
        }
        for (Target t : all_targets())
            if (chosen.count(t)) m.targets.push_back(t);
    } else {
        m.targets = all_targets();
    }
    return m;
}

// ---------------------------------------------------------------------------------------
// JSON description -> builder calls

namespace {

struct Reader {
    const JsonSource& src;
    Diagnostics& diagnostics;

    bool fail(const std::string& pointer, const std::string& what) {
        diagnostics.push_back(src.error(pointer, what));
        return false;
    }
    const Json& at(const std::string& pointer) const { return src.root().at(Json::json_pointer(pointer)); }

    bool keys(const std::string& pointer, const std::vector<std::string>& allowed, const std::vector<std::string>& required) {
        const Json& v = at(pointer);
        if (!v.is_object()) return fail(pointer, "expected an object with keys " + join(allowed) + ", got " + json_describe(v));
        for (const auto& [k, _] : v.items())
            if (std::find(allowed.begin(), allowed.end(), k) == allowed.end())
                return fail(json_child(pointer, k), "unknown key '" + k + "'; expected one of " + join(allowed));
        for (const auto& k : required)
            if (!v.contains(k)) return fail(pointer, "missing key '" + k + "'");
        return true;
    }
    bool string(const std::string& pointer, std::string& out) {
        const Json& v = at(pointer);
        if (!v.is_string()) return fail(pointer, "expected a string, got " + json_describe(v));
        out = v.get<std::string>();
        return true;
    }
    bool number(const std::string& pointer, double& out) {
        const Json& v = at(pointer);
        if (!v.is_number()) return fail(pointer, "expected a number, got " + json_describe(v));
        out = v.get<double>();
        return true;
    }
    bool strings(const std::string& pointer, std::vector<std::string>& out) {
        const Json& v = at(pointer);
        if (!v.is_array()) return fail(pointer, "expected an array of strings, got " + json_describe(v));
        for (size_t i = 0; i < v.size(); ++i) {
            std::string s;
            if (!string(json_child(pointer, i), s)) return false;
            out.push_back(s);
        }
        return true;
    }
    bool numbers(const std::string& pointer, std::vector<double>& out) {
        const Json& v = at(pointer);
        if (v.is_number()) {
            out = {v.get<double>()};
            return true;
        }
        if (!v.is_array()) return fail(pointer, "expected a number or an array of numbers, got " + json_describe(v));
        for (size_t i = 0; i < v.size(); ++i) {
            double x = 0;
            if (!number(json_child(pointer, i), x)) return false;
            out.push_back(x);
        }
        return true;
    }
};

// "axis=choice" of a rule's "if".
bool split_item(Reader& r, const std::string& pointer, std::string& axis, std::string& choice) {
    std::string item;
    if (!r.string(pointer, item)) return false;
    const size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size())
        return r.fail(pointer, "expected \"axis=choice\", got \"" + item + "\"");
    axis = item.substr(0, eq);
    choice = item.substr(eq + 1);
    return true;
}

} // namespace

std::optional<Material> parse_material(const JsonSource& src, Diagnostics& diagnostics) {
    Reader r{src, diagnostics};
    auto bad = [&](const std::string& pointer, const std::string& what) -> std::optional<Material> {
        r.fail(pointer, what);
        return std::nullopt;
    };
    const SourceRef root{&src, ""};
    if (!r.keys("", {"name", "description", "preset", "axes", "rules", "parameters", "targets"}, {"name"})) return std::nullopt;
    std::string name;
    if (!r.string("/name", name)) return std::nullopt;
    MaterialBuilder b(name, root.child("name"));
    const Json& doc = src.root();
    if (doc.contains("description")) {
        std::string d;
        if (!r.string("/description", d)) return std::nullopt;
        b.description(d);
    }
    if (doc.contains("preset")) {
        std::string p;
        if (!r.string("/preset", p)) return std::nullopt;
        b.preset(p, root.child("preset"));
    }
    if (doc.contains("axes")) {
        const Json& a = doc["axes"];
        if (!a.is_object()) return bad("/axes", "expected an object mapping axis names to choice lists, got " + json_describe(a));
        for (const auto& [axis, value] : a.items()) {
            const std::string p = json_child("/axes", axis);
            if (value.is_string() && value.get<std::string>() == "all") {
                b.offer_all(axis, {&src, p});
                continue;
            }
            if (!value.is_array()) return bad(p, "expected an array of choices or \"all\", got " + json_describe(value));
            std::vector<std::string> choices;
            if (!r.strings(p, choices)) return std::nullopt;
            b.offer(axis, choices, {&src, p});
        }
    }
    if (doc.contains("rules")) {
        const Json& rules = doc["rules"];
        if (!rules.is_array()) return bad("/rules", "expected an array of rules, got " + json_describe(rules));
        for (size_t i = 0; i < rules.size(); ++i) {
            const std::string p = json_child("/rules", i);
            if (!r.keys(p, {"if", "requires", "excludes", "why"}, {"if"})) return std::nullopt;
            const Json& rule = rules[i];
            if (rule.contains("requires") == rule.contains("excludes"))
                return bad(p, "expected exactly one of 'requires' or 'excludes'");
            std::string axis, choice, why;
            if (!split_item(r, p + "/if", axis, choice)) return std::nullopt;
            if (rule.contains("why") && !r.string(p + "/why", why)) return std::nullopt;
            const bool is_requires = rule.contains("requires");
            const std::string kp = p + (is_requires ? "/requires" : "/excludes");
            const Json& others = rule[is_requires ? "requires" : "excludes"];
            if (!others.is_object() || others.empty())
                return bad(kp, "expected an object mapping an axis to a list of choices, e.g. {\"waves\": [\"gerstner\"]}, got " +
                                      json_describe(others));
            for (const auto& [other, list] : others.items()) {
                std::vector<std::string> choices;
                if (!r.strings(json_child(kp, other), choices)) return std::nullopt;
                const SourceRef at{&src, json_child(kp, other)};
                if (is_requires) b.requires_choice(axis, choice, other, choices, why, at);
                else b.excludes_choice(axis, choice, other, choices, why, at);
            }
        }
    }
    if (doc.contains("parameters")) {
        const Json& params = doc["parameters"];
        if (!params.is_object()) return bad("/parameters", "expected an object mapping parameter names to settings, got " + json_describe(params));
        for (const auto& [pname, setting] : params.items()) {
            const std::string p = json_child("/parameters", pname);
            if (!r.keys(p, {"value", "min", "max"}, {})) return std::nullopt;
            if (setting.empty()) return bad(p, "expected at least one of 'value', 'min', 'max'");
            if (setting.contains("value")) {
                std::vector<double> v;
                if (!r.numbers(p + "/value", v)) return std::nullopt;
                b.parameter(pname, v, {&src, p + "/value"});
            }
            if (setting.contains("min") != setting.contains("max"))
                return bad(p, std::string("missing key '") + (setting.contains("min") ? "max" : "min") + "': a range needs both");
            if (setting.contains("min")) {
                double lo = 0, hi = 0;
                if (!r.number(p + "/min", lo) || !r.number(p + "/max", hi)) return std::nullopt;
                b.range(pname, lo, hi, {&src, p + "/min"});
            }
        }
    }
    if (doc.contains("targets")) {
        std::vector<std::string> t;
        if (!r.strings("/targets", t)) return std::nullopt;
        b.targets(t, root.child("targets"));
    }
    return b.build(diagnostics);
}

std::optional<Material> load_material(const std::filesystem::path& path, Diagnostics& diagnostics) {
    Diagnostic error;
    const auto src = JsonSource::load(path, &error);
    if (!src) {
        diagnostics.push_back(error);
        return std::nullopt;
    }
    return parse_material(*src, diagnostics);
}

Material default_material() {
    // Keep in step with examples/materials/default.json (a test builds both and compares).
    Diagnostics ds;
    auto m = MaterialBuilder("default")
                 .description("clear sea water: a few choices per axis, enough for every example scene to prune something")
                 .preset("tropical_ocean")
                 .offer("fresnel", {"schlick", "exact"})
                 .offer("extinction", {"absorb_scatter"})
                 .offer("specular", {"none", "blinn_phong"})
                 .offer("foam", {"none", "shore"})
                 .offer("reflection", {"sky_cubemap", "planar_projective"})
                 .offer("refraction", {"screen_distort"})
                 .offer("normals", {"flat"})
                 .offer("waves", {"flat", "gerstner"})
                 .offer("shore", {"hard", "soft"})
                 .offer("precision", {"full", "half"})
                 .excludes_choice("precision", "half", "fresnel", {"exact"},
                                  "the exact Fresnel term is the reference; mobile builds use Schlick")
                 .parameter("absorb_coefficients", {0.46, 0.09, 0.06})
                 .range("absorb_coefficients", 0.05, 2.0)
                 .range("scatter_coefficient", 0.01, 2.0)
                 .parameter("shore_hardness", {1.0})
                 .range("shore_hardness", 0.5, 4.0)
                 .targets({"glsl", "hlsl", "spirv", "glsl330", "essl300", "msl", "reflection"})
                 .build(ds);
    return *m; // the built-in description is valid by construction (tested)
}

} // namespace watergen
