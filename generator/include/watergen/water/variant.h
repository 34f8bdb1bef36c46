// Axes of the water shader and the choices wired on each; a Variant picks one per axis.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace watergen {

struct ChoiceInfo {
    std::string name;        // e.g. "schlick"
    std::string seed;        // article it comes from, e.g. "000"
    std::string description; // one line for --help and reports
    bool gold = false;       // the reference the cheaper choices are measured against
};

struct AxisInfo {
    std::string name;                // e.g. "fresnel"
    std::string default_choice;
    std::vector<ChoiceInfo> choices; // in documentation order
};

// Every axis in fixed order; the order of a variant key.
const std::vector<AxisInfo>& axes();
const AxisInfo* find_axis(const std::string& name);

struct Variant {
    std::vector<std::string> choices; // one per axis, in axes() order

    const std::string& choice(const std::string& axis) const;
    // "fresnel=schlick,extinction=absorb_scatter"
    std::string key() const;
    // "fresnel-schlick_extinction-absorb_scatter": safe as a file name
    std::string file_stem() const;
    // xxHash64 of key(), 16 lower-case hex digits: a short, stable name for logs and caches.
    std::string short_hash() const;
};

Variant default_variant();
// Sets one axis; returns an error message naming the allowed choices on a bad axis or choice.
std::optional<std::string> set_choice(Variant& v, const std::string& axis, const std::string& choice);
// Parses a key as produced by Variant::key(); axes left out keep their default.
std::optional<Variant> parse_variant_key(const std::string& key, std::string* error);
// axis=choice is only valid with requires_axis in requires_choices.
struct Constraint {
    std::string axis, choice;
    std::string requires_axis;
    std::vector<std::string> requires_choices;
    std::string why;
};
const std::vector<Constraint>& constraints();
// The first constraint `v` breaks, as a sentence naming both axes; nullopt when valid.
std::optional<std::string> check_constraints(const Variant& v);

// Visits every valid variant once, in axis order (odometer over the choices). A pure function
// of axes() and constraints().
void for_each_variant(const std::function<void(const Variant&)>& visit);
size_t variant_space_size();

} // namespace watergen
