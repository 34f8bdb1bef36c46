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
#include "watergen/runtime/shader_build.h"

namespace watergen::manifest {

using nlohmann::json;

// The bytes of a regular file of at most 256 MiB; nullopt and `error` naming the file otherwise.
std::optional<std::string> read_bytes(const std::filesystem::path& path, std::string* error);

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

// A variant entry's "passes" (optional): name -> reference (build_pass.cpp).
void read_passes(ManifestReader& r, const json& entry, const std::string& path,
                 std::map<std::string, PassReference>& passes);

} // namespace watergen::manifest
