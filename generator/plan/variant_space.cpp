#include "watergen/plan/variant_space.h"

#include "watergen/ir/text.h"

namespace watergen {

std::vector<Rule> builtin_rules() {
    std::vector<Rule> rules;
    for (const auto& a : axes())
        for (const auto& c : a.choices)
            for (const auto& r : c.requirements)
                rules.push_back(
                    {Rule::Kind::Requires, a.name, c.name, r.axis, r.choices, r.why, ""});
    return rules;
}

std::vector<std::string>& VariantSpace::offered(const std::string& axis) {
    return choices.at(static_cast<size_t>(find_axis(axis) - axes().data()));
}

const std::vector<std::string>& VariantSpace::offered(const std::string& axis) const {
    return choices.at(static_cast<size_t>(find_axis(axis) - axes().data()));
}

VariantSpace full_space() {
    VariantSpace s;
    for (const auto& a : axes()) {
        std::vector<std::string> names;
        for (const auto& c : a.choices)
            names.push_back(c.name);
        s.choices.push_back(std::move(names));
    }
    s.rules = builtin_rules();
    return s;
}

const Rule* find_broken_rule(const std::vector<Rule>& rules, const Variant& v) {
    for (const auto& r : rules) {
        if (v.choice(r.axis) != r.choice) continue;
        const std::string& other = v.choice(r.other_axis);
        bool listed = false;
        for (const auto& c : r.other_choices)
            listed = listed || c == other;
        if (listed != (r.kind == Rule::Kind::Requires)) return &r;
    }
    return nullptr;
}

std::optional<std::string> broken_rule(const std::vector<Rule>& rules, const Variant& v) {
    const Rule* r = find_broken_rule(rules, v);
    if (!r) return std::nullopt;
    const std::string list = join(r->other_choices);
    return r->axis + "=" + r->choice +
           (r->kind == Rule::Kind::Requires ? " requires " : " excludes ") + r->other_axis +
           " in {" + list + "}" + (r->why.empty() ? "" : " (" + r->why + ")") + "; got " +
           r->other_axis + "=" + v.choice(r->other_axis) +
           (r->where.empty() ? "" : " [" + r->where + "]");
}

std::optional<std::string> check_constraints(const Variant& v) {
    static const std::vector<Rule> rules = builtin_rules();
    return broken_rule(rules, v);
}

void enumerate(const VariantSpace& space, const std::function<void(const Variant&)>& visit) {
    const size_t n = space.choices.size();
    if (n != axes().size()) return;
    for (const auto& list : space.choices)
        if (list.empty()) return;
    Variant v = default_variant();
    std::vector<size_t> index(n, 0);
    for (;;) {
        for (size_t a = 0; a < n; ++a)
            v.choices[a] = space.choices[a][index[a]];
        if (!broken_rule(space.rules, v)) visit(v);
        size_t a = n;
        while (a > 0) {
            --a;
            if (++index[a] < space.choices[a].size()) break;
            index[a] = 0;
            if (a == 0) return;
        }
    }
}

size_t count_variants(const VariantSpace& space) {
    size_t n = 0;
    enumerate(space, [&](const Variant&) { ++n; });
    return n;
}

} // namespace watergen
