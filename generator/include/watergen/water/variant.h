// A Variant picks one choice per axis of the registry (axis_registry.h); its key names it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "watergen/water/axis_registry.h"

namespace watergen {

struct Variant {
    std::vector<std::string> choices; // one per axis, in axes() order

    const std::string& choice(const std::string& axis) const;
    // "fresnel=schlick,extinction=absorb_scatter"
    std::string key() const;
    // "fresnel-schlick_extinction-absorb_scatter": safe as a file name (capped_file_stem).
    std::string file_stem() const;
    // xxHash64 of key(), 16 lower-case hex digits: a short, stable name for logs and caches.
    std::string short_hash() const;
};

// File systems cap a name at 255 bytes (ext4, XFS, APFS, NTFS), and a directory named for a
// variant of many long choices passes that (the full space has names of 258), so a stem longer
// than kMaxFileStem keeps its first kMaxFileStem - 17 bytes, then '-' and the 16 hex digits of
// the xxHash64 of `key` (unique as the key is). The margin leaves room for what is appended to
// a stem: "_view-reflection" (render) and ".frag.spv" (frozen modules).
constexpr size_t kMaxFileStem = 224;
std::string capped_file_stem(std::string stem, const std::string& key);

Variant default_variant();
// Sets one axis; returns an error message naming the allowed choices on a bad axis or choice.
std::optional<std::string> set_choice(Variant& v, const std::string& axis,
                                      const std::string& choice);
// Parses a key as produced by Variant::key(); axes left out keep their default.
std::optional<Variant> parse_variant_key(const std::string& key, std::string* error);

} // namespace watergen
