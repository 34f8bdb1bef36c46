// A manifest walked against the table of runtime/manifest_schema.h: the key paths of its members
// and elements ("*" for an element of an array and for a member of a Map), and those the table
// lacks or types otherwise. For the tests that hold a manifest to the schema (the checked-in
// build's, the specialized and branching builds').
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <string_view>

#include "watergen/runtime/manifest_schema.h"

namespace watergen::test {

// The table's entry for `path`; null for a path it lacks.
inline const manifest_schema::ManifestKey* schema_key(std::string_view path) {
    static const std::map<std::string_view, const manifest_schema::ManifestKey*> by_path = [] {
        std::map<std::string_view, const manifest_schema::ManifestKey*> keys;
        for (const manifest_schema::ManifestKey& k : manifest_schema::kManifestKeys)
            keys.emplace(k.path, &k);
        return keys;
    }();
    const auto it = by_path.find(path);
    return it == by_path.end() ? nullptr : it->second;
}

inline const char* json_type_name(manifest_schema::JsonType type) {
    using T = manifest_schema::JsonType;
    switch (type) {
    case T::String:
        return "a string";
    case T::Integer:
        return "a non-negative integer";
    case T::Number:
        return "a number";
    case T::Boolean:
        return "a boolean";
    case T::Array:
        return "an array";
    case T::Object:
        return "an object";
    case T::Map:
        return "an object of names";
    }
    return "?";
}

template <class Json> bool has_json_type(const Json& v, manifest_schema::JsonType type) {
    using T = manifest_schema::JsonType;
    switch (type) {
    case T::String:
        return v.is_string();
    case T::Integer:
        return v.is_number_unsigned() ||
               (v.is_number_integer() && v.template get<std::int64_t>() >= 0);
    case T::Number:
        return v.is_number();
    case T::Boolean:
        return v.is_boolean();
    case T::Array:
        return v.is_array();
    case T::Object:
    case T::Map:
        return v.is_object();
    }
    return false;
}

namespace detail {

// Below `v` at `path` ("" for the document): every path into `paths`, or, with `faults`, each
// member or element the table lacks (and nothing below it) or types otherwise.
template <class Json>
void walk_schema(const Json& v, const std::string& path, std::set<std::string>* paths,
                 std::set<std::string>* faults) {
    const manifest_schema::ManifestKey* here = path.empty() ? nullptr : schema_key(path);
    auto below = [&](const std::string& p, const Json& x) {
        if (paths) paths->insert(p);
        if (faults) {
            const manifest_schema::ManifestKey* key = schema_key(p);
            if (!key) {
                faults->insert(p + ": not in runtime/manifest_schema.h's kManifestKeys");
                return;
            }
            if (!has_json_type(x, key->type))
                faults->insert(p + ": expected " + json_type_name(key->type));
        }
        walk_schema(x, p, paths, faults);
    };
    if (v.is_object()) {
        const bool names = here && here->type == manifest_schema::JsonType::Map;
        for (auto it = v.begin(); it != v.end(); ++it)
            below(path + "/" + (names ? std::string("*") : it.key()), it.value());
    } else if (v.is_array()) {
        for (const auto& x : v)
            below(path + "/*", x);
    }
}

} // namespace detail

// The key path of every member and element below `v`, which is at `path` ("" for a document).
template <class Json>
std::set<std::string> key_paths(const Json& v, const std::string& path = std::string()) {
    std::set<std::string> paths;
    detail::walk_schema(v, path, &paths, nullptr);
    return paths;
}

// "<path>: why" for each key path of the document `doc` the table lacks or types otherwise.
template <class Json> std::set<std::string> unschemed_paths(const Json& doc) {
    std::set<std::string> faults;
    detail::walk_schema(doc, std::string(), nullptr, &faults);
    return faults;
}

} // namespace watergen::test
