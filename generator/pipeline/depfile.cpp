#include "watergen/pipeline/depfile.h"

#include "watergen/pipeline/output_writer.h"

namespace watergen {

std::optional<std::string> escape_depfile_path(const std::string& path) {
    if (path.empty() || path.find_first_of("\n\r") != std::string::npos) return std::nullopt;
    std::string out;
    size_t backslashes = 0; // run of backslashes just copied
    for (char c : path) {
        if (c == ' ' || c == '#') {
            // Make and ninja read 2N+1 backslashes and a space as N backslashes and a space.
            out.append(backslashes, '\\');
            out += '\\';
        } else if (c == '$') {
            out += '$'; // ninja's escape; make reads "$$" as '$' too
        }
        out += c;
        backslashes = c == '\\' ? backslashes + 1 : 0;
    }
    // A backslash before the separating space would escape it.
    out.append(backslashes, '\\');
    return out;
}

std::optional<std::string> depfile_text(const std::string& target,
                                        const std::vector<std::string>& prerequisites,
                                        std::string* error) {
    auto escaped = [&](const std::string& path) {
        auto e = escape_depfile_path(path);
        if (!e && error)
            *error = "cannot name '" + path +
                     "' in a dependency file: expected a non-empty path without line breaks";
        return e;
    };
    const auto head = escaped(target);
    if (!head) return std::nullopt;
    std::string text = *head + ":";
    for (const std::string& p : prerequisites) {
        const auto e = escaped(p);
        if (!e) return std::nullopt;
        text += " \\\n  " + *e;
    }
    return text + "\n";
}

std::optional<std::string> write_depfile(const std::string& file, const std::string& target,
                                         const std::vector<std::string>& prerequisites) {
    std::string error;
    const auto text = depfile_text(target, prerequisites, &error);
    if (!text) return file + ": " + error;
    return write_file_atomically(file, *text);
}

} // namespace watergen
