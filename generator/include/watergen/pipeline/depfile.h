// Makefile-style dependency files (`watergen build --depfile FILE`): one target, the files it
// was made from, escaped so that make, ninja and CMake's depfile reader all split them back
// into the same paths. A build system that reads it reruns watergen when one of them changes.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace watergen {

// One path as a depfile names it: ' ' and '#' after a backslash (the backslashes before them
// doubled), '$' doubled, trailing backslashes doubled. nullopt for a path no depfile can
// hold (a newline or carriage return in it, or empty).
std::optional<std::string> escape_depfile_path(const std::string& path);

// "<target>: \\\n  <prerequisite> \\\n  ...\n"; nullopt and *error naming the path when one
// cannot be escaped.
std::optional<std::string> depfile_text(const std::string& target,
                                        const std::vector<std::string>& prerequisites,
                                        std::string* error);

// depfile_text written to `file` atomically (temporary beside it, then rename); the error
// names the file or the path that cannot be written into one.
std::optional<std::string> write_depfile(const std::string& file, const std::string& target,
                                         const std::vector<std::string>& prerequisites);

} // namespace watergen
