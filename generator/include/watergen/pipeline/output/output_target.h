// The directory a build may replace. A build puts its output in place of the directory it is
// given, as a whole; so that directory must be one watergen made (it holds the manifest.json of
// a build, or the build record shows watergen wrote it), an empty directory, or a path that does
// not exist yet. Anything else (a regular
// file, a device, a symbolic link, a directory of other files, the current directory or one
// holding it) is refused, and left untouched.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace watergen {

struct OutputTarget {
    std::filesystem::path path; // absolute and normal: "out/", "." and "a/../out" resolved
    std::string error;          // non-empty: refused, why (with errno's text where a call failed)
    bool ok() const { return error.empty(); }
};

// `recorded`: the files the build record of `out` says watergen wrote there (build_record.h);
// a directory whose manifest.json is broken is still replaced when it holds only those.
OutputTarget check_output_target(const std::filesystem::path& out,
                                 const std::vector<std::string>& recorded = {});
// `out` absolute and normal, without a trailing separator ("out/" and "./out" are "$PWD/out").
std::filesystem::path normal_output_path(const std::filesystem::path& out);

// Whether `inner` is `outer` or lies below it (both absolute and normal; compared by component).
bool path_holds(const std::filesystem::path& outer, const std::filesystem::path& inner);

// Whether `bytes` are a manifest.json that watergen wrote (a JSON object whose "generator"
// names watergen).
bool is_watergen_manifest(const std::string& bytes);
// Whether `path` is a regular file that begins as a watergen manifest: its "generator" member
// is read, not the rest (a manifest of many variants is large).
bool is_watergen_manifest_file(const std::filesystem::path& path);

} // namespace watergen
