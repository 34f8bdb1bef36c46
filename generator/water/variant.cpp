#include "watergen/water/variant.h"

#include <cstdio>

// Header-only use of xxHash: core needs no extra link dependency for one hash.
#define XXH_INLINE_ALL
#include <xxhash.h>

#include "watergen/ir/core/text.h"

namespace watergen {

namespace {

size_t axis_index(const std::string& name) {
    const auto& list = axes();
    for (size_t i = 0; i < list.size(); ++i)
        if (list[i].name == name) return i;
    return list.size();
}

std::string joined_names(const AxisInfo& a) {
    return join(a.choices, [](const ChoiceInfo& c) { return c.name; });
}

} // namespace

const std::string& Variant::choice(const std::string& axis) const {
    static const std::string none;
    const size_t i = axis_index(axis);
    return i < choices.size() ? choices[i] : none;
}

namespace {

// "axis<bind>choice" for every axis (but one left out at its default, keyed_at_default),
// `separator` between them (a build makes one per variant of the space, 3,502,080 for a shard
// of the full space, the_full_space_has_3502080_variants: one string, no parts).
std::string spell(const std::vector<std::string>& choices, char bind, char separator) {
    std::string s;
    s.reserve(256);
    for (size_t i = 0; i < axes().size(); ++i) {
        const AxisInfo& a = axes()[i];
        if (!spelled_in_key(a, choices[i])) continue;
        if (i) s += separator;
        s += a.name;
        s += bind;
        s += choices[i];
    }
    return s;
}

} // namespace

std::string Variant::key() const {
    return spell(choices, '=', ',');
}

namespace {

std::string hash_hex(const std::string& text) {
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx",
                  static_cast<unsigned long long>(XXH64(text.data(), text.size(), 0)));
    return hex;
}

} // namespace

std::string capped_file_stem(std::string stem, const std::string& key) {
    if (stem.size() <= kMaxFileStem) return stem;
    stem.resize(kMaxFileStem - 17);
    return stem + "-" + hash_hex(key);
}

std::string Variant::file_stem() const {
    return capped_file_stem(spell(choices, '-', '_'), key());
}

std::string Variant::short_hash() const {
    return hash_hex(key());
}

Variant default_variant() {
    Variant v;
    for (const auto& a : axes())
        v.choices.push_back(a.default_choice);
    return v;
}

std::optional<std::string> set_choice(Variant& v, const std::string& axis,
                                      const std::string& choice) {
    const size_t i = axis_index(axis);
    if (i == axes().size()) {
        const std::string names = join(axes(), [](const AxisInfo& a) { return a.name; });
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

} // namespace watergen
