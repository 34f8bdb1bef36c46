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

// Writes one file through a temporary in the same directory and a rename.
std::optional<std::string> write_file_atomically(const std::filesystem::path& path, const std::string& contents);

} // namespace watergen
