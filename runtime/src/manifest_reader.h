// Reading the JSON a build writes (manifest.json, a pass's pass.json) without exceptions: each
// accessor checks the type first and records the first problem as "<file>: <key path>:
// expected ...". Private to watergen_runtime (shader_build.cpp, build_pass.cpp); not installed.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "watergen/runtime/build_pass.h"
#include "watergen/runtime/manifest_schema.h"
#include "watergen/runtime/shader_build.h"

namespace watergen::manifest {

using nlohmann::json;
// The manifest's keys (manifest_schema.h), as the readers spell them.
namespace mk = manifest_schema;

// The largest manifest.json: the generator's own limit on the manifest it writes and reads back
// (generator/pipeline/output/output_target.cpp); a build of more variants does not open anywhere.
constexpr std::uintmax_t kMaxManifestBytes = std::uintmax_t(256) << 20;
// The largest pass.json or reflection file: the generator writes a few KB (one uniform block of
// at most kMaxBlockMembers members, a few bindings); 1 MiB is far beyond any of them.
constexpr std::uintmax_t kMaxDescriptionBytes = std::uintmax_t(1) << 20;

// What a manifest's JSON can hold (json_limits.h), checked before its DOM is built. The
// generator's manifests average 24 bytes per JSON value, keys included (paths, keys, hashes:
// generated/manifest.json, the default material's build, is 34,336 values in 834,164 bytes): a
// manifest at kMaxManifestBytes holds about 11M values, so 16M refuses no build the generator
// can write, while a text of small values ("[0,0,0,...", "[],[],...") no longer makes a DOM of
// 20 times its size. The generator nests 8 levels; strings are paths, keys and descriptions.
constexpr size_t kMaxManifestValues = size_t(16) << 20;
constexpr size_t kMaxManifestDepth = 16;
constexpr size_t kMaxManifestString = size_t(64) << 10;
// What the variants read from a manifest may hold in memory in all. The specialized and
// branching modes copy their shader's part (files, uniform block, textures) into every variant
// that is drawn with it, so a few shaders of a huge uniform block times many small variant
// entries would be a product of two counts; the copies are counted (estimated_bytes()) and
// the manifest refused past this. A real variant holds about 11 KB (the 56 of the default
// material's build: docs/engine-guide.md), so 1 GiB is some 95,000 variants of that size.
constexpr size_t kMaxVariantBytes = size_t(1) << 30;

// The bytes a variant's strings, numbers and entries take, roughly (for kMaxVariantBytes).
size_t estimated_bytes(const BuildVariant& v);

// The bytes of a regular file of at most `max_bytes`; nullopt and `error` naming the file
// otherwise.
std::optional<std::string> read_bytes(const std::filesystem::path& path, std::string* error,
                                      std::uintmax_t max_bytes = kMaxManifestBytes);

// Walks the manifest recording the first problem as "<file>: <key path>: expected ...";
// every accessor checks the type first, so nlohmann never throws.
class ManifestReader {
  public:
    ManifestReader(std::string file, std::string* error) : file_(std::move(file)), error_(error) {}

    const json* get(const json& object, const std::string& path, const char* key,
                    json::value_t type, const char* expected, bool required = true) {
        if (failed_) return nullptr;
        const std::string where = path.empty() ? key : path + "." + key;
        if (!object.is_object() || !object.contains(key)) {
            if (required) fail(where, std::string("missing; expected ") + expected);
            return nullptr;
        }
        const json& v = object[key];
        const bool number =
            type == json::value_t::number_float && (v.is_number_float() || v.is_number_integer());
        if (v.type() != type && !number &&
            !(type == json::value_t::number_unsigned && v.is_number_unsigned())) {
            fail(where, std::string("expected ") + expected);
            return nullptr;
        }
        return &v;
    }
    std::string text(const json& o, const std::string& path, const char* key,
                     bool required = true) {
        const json* v = get(o, path, key, json::value_t::string, "a string", required);
        return v ? v->get<std::string>() : std::string();
    }
    uint32_t u32(const json& o, const std::string& path, const char* key) {
        const json* v = get(o, path, key, json::value_t::number_unsigned, "an unsigned integer");
        if (v && v->get<uint64_t>() > UINT32_MAX) fail(path + "." + key, "out of range");
        return v && !failed_ ? static_cast<uint32_t>(v->get<uint64_t>()) : 0;
    }
    std::vector<double> numbers(const json& o, const std::string& path, const char* key,
                                bool required = true) {
        std::vector<double> out;
        const json* v = get(o, path, key, json::value_t::array, "an array of numbers", required);
        if (!v) return out;
        for (const json& n : *v) {
            if (!n.is_number()) {
                fail(path + "." + key, "expected an array of numbers");
                return {};
            }
            out.push_back(n.get<double>());
        }
        return out;
    }
    void fail(const std::string& where, const std::string& what) {
        if (failed_) return;
        failed_ = true;
        *error_ = file_ + ": " + where + ": " + what;
    }
    bool failed() const { return failed_; }

  private:
    std::string file_;
    std::string* error_;
    bool failed_ = false;
};

// "path[i]".
std::string at(const std::string& path, size_t i);

// An entry's "files" (kind -> paths), required.
void read_file_lists(ManifestReader& r, const json& entry, const std::string& path,
                     std::map<std::string, std::vector<std::string>>& files);
// parent."uniform_block" (optional; an empty object is none) into v.block_name and
// v.parameters.
void read_uniform_block(ManifestReader& r, const json& parent, const std::string& path,
                        BuildVariant& v);

// The manifest's "bindings": the map's name, each resource's slot, and with a push_constant
// slot (at most one) the range's "push_constant_bytes" (required then; 4..4096, a multiple of 4).
BuildBindings read_bindings(ManifestReader& r, const json& bindings);

// A variant entry's "passes" (optional): name -> reference (build_pass.cpp).
void read_passes(ManifestReader& r, const json& entry, const std::string& path,
                 std::map<std::string, PassReference>& passes);

} // namespace watergen::manifest
