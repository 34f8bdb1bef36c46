// The permutation space as a pure function of its description: per axis the choices on
// offer, plus rules between choices (requires / excludes). The full space is every choice of
// axes() under the requirements the registry's choices declare; a material narrows the choices
// and may add its own rules. The only enumeration of variants in watergen.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "watergen/water/variant.h"

namespace watergen {

struct Rule {
    enum class Kind { Requires, Excludes };
    Kind kind = Kind::Requires;
    // Requires: axis=choice is only valid with other_axis in other_choices.
    // Excludes: axis=choice is invalid with other_axis in other_choices.
    std::string axis, choice;
    std::string other_axis;
    std::vector<std::string> other_choices;
    std::string why;
    std::string where; // "file:line:col" or "" for built-in rules; shown in messages
};

struct VariantSpace {
    std::vector<std::vector<std::string>> choices; // per axis in axes() order, documentation order
    std::vector<Rule> rules;

    // The choices on offer on the axis named `axis` (which must be one of axes()).
    std::vector<std::string>& offered(const std::string& axis);
    const std::vector<std::string>& offered(const std::string& axis) const;
};

// The requirements of every choice of the registry (ChoiceInfo::requirements) as rules, in
// axis and choice order.
std::vector<Rule> builtin_rules();
// Every choice of every axis under builtin_rules() (its size: count_variants(full_space())).
VariantSpace full_space();

// The first rule `v` breaks, or nullptr when it breaks none.
const Rule* find_broken_rule(const std::vector<Rule>& rules, const Variant& v);
// The same as a sentence naming both axes; nullopt when valid.
std::optional<std::string> broken_rule(const std::vector<Rule>& rules, const Variant& v);
// broken_rule(builtin_rules(), v): why `v` is no variant of the full space; nullopt when valid.
std::optional<std::string> check_constraints(const Variant& v);

// Visits every valid variant of the space once, odometer order over axes() (the last axis
// turns fastest). Cost: product of the choice counts x rules.
void enumerate(const VariantSpace& space, const std::function<void(const Variant&)>& visit);
// The same over choice indices (index[a]: the position in space.choices[a]), making no Variant.
void enumerate_indices(const VariantSpace& space,
                       const std::function<void(const std::vector<size_t>&)>& visit);
size_t count_variants(const VariantSpace& space);

} // namespace watergen
