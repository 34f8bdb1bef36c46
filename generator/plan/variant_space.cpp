#include "watergen/plan/variant_space.h"

#include <algorithm>
#include <optional>

#include "watergen/ir/core/text.h"

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

namespace {

// A rule over the space's choice indices: it fires when `axis` is at `choice`, and is broken
// when `allowed[index of other_axis]` is false (a Requires rule allows the listed choices, an
// Excludes rule the others).
struct IndexedRule {
    size_t axis, choice, other_axis;
    std::vector<bool> allowed;
};

// The rules as index tests; nullopt when one names an axis that does not exist (then the
// names are compared, as broken_rule does).
std::optional<std::vector<IndexedRule>> index_rules(const VariantSpace& space) {
    std::vector<IndexedRule> indexed;
    for (const Rule& r : space.rules) {
        const AxisInfo* a = find_axis(r.axis);
        const AxisInfo* o = find_axis(r.other_axis);
        if (!a || !o) return std::nullopt;
        const size_t ai = static_cast<size_t>(a - axes().data());
        const size_t oi = static_cast<size_t>(o - axes().data());
        std::vector<bool> allowed;
        for (const std::string& c : space.choices[oi]) {
            const bool listed = std::find(r.other_choices.begin(), r.other_choices.end(), c) !=
                                r.other_choices.end();
            allowed.push_back(listed == (r.kind == Rule::Kind::Requires));
        }
        for (size_t k = 0; k < space.choices[ai].size(); ++k) // no index: never fires here
            if (space.choices[ai][k] == r.choice) indexed.push_back({ai, k, oi, allowed});
    }
    return indexed;
}

} // namespace

void enumerate_indices(const VariantSpace& space,
                       const std::function<void(const std::vector<size_t>&)>& visit) {
    const size_t n = space.choices.size();
    if (n != axes().size()) return;
    for (const auto& list : space.choices)
        if (list.empty()) return;
    // The full space has millions of variants (3,502,080: the_full_space_has_3502080_variants)
    // and a build enumerates it several times: rules are tested on indices, and no names are
    // touched.
    const std::optional<std::vector<IndexedRule>> rules = index_rules(space);
    Variant named = default_variant(); // only when a rule names an unknown axis
    std::vector<size_t> index(n, 0);
    for (;;) {
        bool valid = true;
        if (rules) {
            for (const IndexedRule& r : *rules)
                if (index[r.axis] == r.choice && !r.allowed[index[r.other_axis]]) {
                    valid = false;
                    break;
                }
        } else {
            for (size_t a = 0; a < n; ++a)
                named.choices[a] = space.choices[a][index[a]];
            valid = !find_broken_rule(space.rules, named);
        }
        if (valid) visit(index);
        size_t a = n;
        while (a > 0) {
            --a;
            if (++index[a] < space.choices[a].size()) break;
            index[a] = 0;
            if (a == 0) return;
        }
    }
}

void enumerate(const VariantSpace& space, const std::function<void(const Variant&)>& visit) {
    Variant v = default_variant();
    enumerate_indices(space, [&](const std::vector<size_t>& index) {
        for (size_t a = 0; a < index.size(); ++a)
            v.choices[a] = space.choices[a][index[a]];
        visit(v);
    });
}

size_t count_variants(const VariantSpace& space) {
    size_t n = 0;
    enumerate_indices(space, [&](const std::vector<size_t>&) { ++n; });
    return n;
}

} // namespace watergen
