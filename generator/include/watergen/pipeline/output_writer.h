// Writes a set of files so that a reader never sees a half-written result.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>

namespace watergen {

// Writes `files` (relative path -> contents) into a fresh sibling of `dir`, then replaces
// `dir` with it by rename. On failure `dir` is left as it was and the error names the path.
std::optional<std::string> write_directory_atomically(const std::filesystem::path& dir,
                                                      const std::map<std::string, std::string>& files);

// A fresh, empty staging directory beside `dir` for writers that produce files themselves;
// publish it with commit_directory(staging, dir), or remove it on failure.
std::filesystem::path make_staging_directory(const std::filesystem::path& dir, std::string* error);
// Replaces `dir` with `staging` by rename; the old `dir` stays complete until then.
std::optional<std::string> commit_directory(const std::filesystem::path& staging, const std::filesystem::path& dir);

// Writes one file through a temporary in the same directory and a rename.
std::optional<std::string> write_file_atomically(const std::filesystem::path& path, const std::string& contents);

} // namespace watergen
