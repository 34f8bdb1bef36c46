// Makefile-style dependency files (`watergen build --depfile FILE`): one target, the files it
// was made from, escaped so that make, ninja and CMake's depfile reader all split them back
// into the same paths. A build system that reads it reruns watergen when one of them changes.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace watergen {

// One path as a depfile names it: ' ', '#' and ':' after a backslash (the backslashes before
// them doubled), '$' doubled, trailing backslashes doubled; make and ninja both read that back.
// nullopt for a path neither can read back whatever the escaping: empty, or with a line break,
// tab, quote or any of ; | % = * ?.
std::optional<std::string> escape_depfile_path(const std::string& path);

// "<target>: \\\n  <prerequisite> \\\n  ...\n"; nullopt and *error naming the path when one
// cannot be escaped.
std::optional<std::string> depfile_text(const std::string& target,
                                        const std::vector<std::string>& prerequisites,
                                        std::string* error);

// Why `file` may not be the dependency file of a build of `inputs` into `out`, or "" when it may:
// a depfile replaces only a path that does not exist or a regular file watergen wrote (the form
// depfile_text writes), never an input (by path or by link), a file inside the output directory
// or inside an earlier watergen output, a directory, a link, a device or a FIFO.
std::string depfile_refusal(const std::filesystem::path& file,
                            const std::vector<std::string>& inputs,
                            const std::filesystem::path& out);

// depfile_text written to `file` atomically (temporary beside it, then rename); the error
// names the file or the path that cannot be written into one.
std::optional<std::string> write_depfile(const std::string& file, const std::string& target,
                                         const std::vector<std::string>& prerequisites);

} // namespace watergen
