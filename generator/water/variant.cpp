#include "watergen/water/variant.h"

#include <algorithm>
#include <cstdio>
#include <functional>

// Header-only use of xxHash: core needs no extra link dependency for one hash.
#define XXH_INLINE_ALL
#include <xxhash.h>

namespace watergen {

const std::vector<AxisInfo>& axes() {
    // Order is the order of a variant key. Seeds: 000 Toman, 001 Lombard, 002 Mihalik,
    // 003 IceFall, 004 sum of sines / Gerstner / Atlas (../shared/docs/water-models.md).
    static const std::vector<AxisInfo> list = {
        {"fresnel",
         "schlick",
         {
             {"none", "", "constant reflectance", false},
             {"power", "002", "F = (1 - c)^q, q = 4.5", false},
             {"schlick", "000", "Schlick's approximation, R0 from the indices", false},
             {"exact", "", "unpolarised dielectric reflectance with total internal reflection", true},
         }},
        {"extinction",
         "absorb_scatter",
         {
             {"none", "", "refracted colour unchanged", false},
             {"linear", "000", "per-channel linear fades with depth and with horizontal visibility", false},
             {"exponential", "002", "exponential fog towards the water colour, a = exp(-d k)", false},
             {"absorb_scatter", "003", "exponential absorption plus scatter colour", false},
             {"beer_lambert", "", "physical per-channel absorption of pure water (Pope and Fry 1997)", true},
         }},
        {"specular",
         "blinn_phong",
         {
             {"none", "", "no sun highlight", false},
             {"toman_glare", "000", "reflected-eye glare, pow(d, 512) scaled by shininess", false},
             {"blinn_phong", "", "pow(N.H, s)", false},
             {"ggx_sun", "004", "GGX microfacet sun lobe with Smith masking and Schlick Fresnel", true},
         }},
        {"foam",
         "none",
         {
             {"none", "", "no foam", false},
             {"shore", "000", "foam band along the shoreline by depth", false},
             {"crest", "000", "foam on wave crests by height", false},
             {"both", "000", "shore and crest foam", false},
         }},
        {"reflection",
         "sky_cubemap",
         {
             {"none", "", "constant sky colour", false},
             {"sky_cubemap", "001", "environment cubemap along reflect(-V, N), fallback below the horizon", false},
             {"planar_projective", "001", "planar reflection texture, projective uv displaced by the normal", false},
             {"fourier_horizon", "003", "sky above a per-texel horizon from 8 Fourier coefficients, trig-free", false},
         }},
        {"refraction",
         "screen_distort",
         {
             {"none", "", "scene colour at the pixel", false},
             {"screen_distort", "000", "scene colour at uv displaced by the normal", false},
             {"refracted_ray", "002", "scene colour where the refracted ray W = U + dv R meets the bed", false},
         }},
        {"normals",
         "flat",
         {
             {"flat", "", "(0, 1, 0)", false},
             {"heightmap_diff", "000", "central differences of the height map", false},
             {"detail_map", "000", "detail normal map in a derivative tangent frame (Schuler)", false},
             {"analytic", "004", "exact normal of the wave model", true},
         }},
        {"waves",
         "flat",
         {
             {"flat", "", "the water plane", false},
             {"sum_of_sines", "004", "sum of sines, frequency x1.18 and amplitude x0.82 per wave", false},
             {"gerstner", "004", "Gerstner waves", false},
             {"heightmap_march", "000", "height-map march, 4 iterations", false},
             {"heightmap_march_converged", "000", "height-map march, 32 iterations", true},
         }},
        {"shore",
         "soft",
         {
             {"hard", "000", "the water colour up to the shoreline", false},
             {"soft", "000", "blend towards the refracted scene by depth x shore hardness", false},
         }},
        {"precision",
         "full",
         {
             {"full", "", "32-bit float everywhere", true},
             {"half", "", "shading math in mediump / min16float (positions stay 32-bit)", false},
         }},
    };
    return list;
}

const std::vector<Constraint>& constraints() {
    static const std::vector<Constraint> list = {
        {"normals", "analytic", "waves", {"sum_of_sines", "gerstner"},
         "analytic normals are the derivatives of a closed-form wave model"},
        {"foam", "crest", "waves", {"sum_of_sines", "gerstner", "heightmap_march", "heightmap_march_converged"},
         "crest foam needs wave heights"},
        {"foam", "both", "waves", {"sum_of_sines", "gerstner", "heightmap_march", "heightmap_march_converged"},
         "crest foam needs wave heights"},
    };
    return list;
}

std::optional<std::string> check_constraints(const Variant& v) {
    for (const auto& c : constraints()) {
        if (v.choice(c.axis) != c.choice) continue;
        const std::string& other = v.choice(c.requires_axis);
        bool allowed = false;
        for (const auto& ok : c.requires_choices) allowed = allowed || ok == other;
        if (!allowed) {
            std::string list;
            for (const auto& ok : c.requires_choices) list += (list.empty() ? "" : ", ") + ok;
            return c.axis + "=" + c.choice + " requires " + c.requires_axis + " in {" + list + "} (" + c.why + "); got " +
                   c.requires_axis + "=" + other;
        }
    }
    return std::nullopt;
}

const AxisInfo* find_axis(const std::string& name) {
    for (const auto& a : axes())
        if (a.name == name) return &a;
    return nullptr;
}

namespace {

size_t axis_index(const std::string& name) {
    const auto& list = axes();
    for (size_t i = 0; i < list.size(); ++i)
        if (list[i].name == name) return i;
    return list.size();
}

std::string joined_names(const AxisInfo& a) {
    std::string s;
    for (const auto& c : a.choices) s += (s.empty() ? "" : ", ") + c.name;
    return s;
}

} // namespace

const std::string& Variant::choice(const std::string& axis) const {
    static const std::string none;
    const size_t i = axis_index(axis);
    return i < choices.size() ? choices[i] : none;
}

std::string Variant::key() const {
    std::string s;
    for (size_t i = 0; i < axes().size(); ++i)
        s += (i ? "," : "") + axes()[i].name + "=" + choices[i];
    return s;
}

std::string Variant::file_stem() const {
    std::string s;
    for (size_t i = 0; i < axes().size(); ++i)
        s += (i ? "_" : "") + axes()[i].name + "-" + choices[i];
    return s;
}

std::string Variant::short_hash() const {
    const std::string k = key();
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(XXH64(k.data(), k.size(), 0)));
    return hex;
}

Variant default_variant() {
    Variant v;
    for (const auto& a : axes()) v.choices.push_back(a.default_choice);
    return v;
}

std::optional<std::string> set_choice(Variant& v, const std::string& axis, const std::string& choice) {
    const size_t i = axis_index(axis);
    if (i == axes().size()) {
        std::string names;
        for (const auto& a : axes()) names += (names.empty() ? "" : ", ") + a.name;
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

void for_each_variant(const std::function<void(const Variant&)>& visit) {
    const auto& list = axes();
    Variant v = default_variant();
    std::vector<size_t> index(list.size(), 0);
    for (;;) {
        for (size_t a = 0; a < list.size(); ++a) v.choices[a] = list[a].choices[index[a]].name;
        if (!check_constraints(v)) visit(v);
        size_t a = list.size();
        while (a > 0) {
            --a;
            if (++index[a] < list[a].choices.size()) break;
            index[a] = 0;
            if (a == 0) return;
        }
    }
}

size_t variant_space_size() {
    size_t n = 0;
    for_each_variant([&](const Variant&) { ++n; });
    return n;
}

} // namespace watergen
