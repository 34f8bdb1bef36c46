// The directory a build may replace. A build puts its output in place of the directory it is
// given, as a whole; so that directory must be one watergen made (it holds the manifest.json of
// a build), an empty directory, or a path that does not exist yet. Anything else (a regular
// file, a device, a symbolic link, a directory of other files, the current directory or one
// holding it) is refused, and left untouched.
#pragma once

#include <filesystem>
#include <string>

namespace watergen {

struct OutputTarget {
    std::filesystem::path path; // absolute and normal: "out/", "." and "a/../out" resolved
    std::string error;          // non-empty: refused, why (with errno's text where a call failed)
    bool ok() const { return error.empty(); }
};

OutputTarget check_output_target(const std::filesystem::path& out);
// `out` absolute and normal, without a trailing separator ("out/" and "./out" are "$PWD/out").
std::filesystem::path normal_output_path(const std::filesystem::path& out);

// Whether `bytes` are a manifest.json that watergen wrote (a JSON object whose "generator"
// names watergen).
bool is_watergen_manifest(const std::string& bytes);

} // namespace watergen
