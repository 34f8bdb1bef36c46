#include "watergen/pipeline/output/depfile.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <sys/stat.h>

#include "watergen/pipeline/output/output_target.h"
#include "watergen/pipeline/output/output_writer.h"
#include "watergen/pipeline/output/safe_read.h"

namespace watergen {

namespace fs = std::filesystem;

namespace {

// Characters make or ninja cannot read back in a path, whatever the escaping: a line break ends
// the rule; a tab, ';', '|' and '=' end or change the rule for make (a recipe, order-only
// prerequisites, a target-specific variable); '%' makes a pattern rule; '*' and '?' are make's
// wildcards; quotes are kept by one reader and not the other.
constexpr const char* kInexpressible = "\n\r\t;|%=*?\"'";

// A depfile is a few lines per input; a file far larger is not one watergen wrote.
constexpr size_t kMaxDepfileBytes = size_t(1) << 20;

// Whether `text` has the form depfile_text writes: "<...>manifest.json: \" on the first line,
// every later line "  <path>" with a continuation on all but the last, and a final newline.
bool looks_like_our_depfile(const std::string& text) {
    const size_t eol = text.find('\n');
    if (eol == std::string::npos || text.back() != '\n') return false;
    const std::string head = text.substr(0, eol);
    const std::string suffix = "manifest.json:";
    const bool alone = head.size() >= suffix.size() &&
                       head.compare(head.size() - suffix.size(), suffix.size(), suffix) == 0;
    const bool continued =
        head.size() >= suffix.size() + 2 &&
        head.compare(head.size() - suffix.size() - 2, suffix.size() + 2, suffix + " \\") == 0;
    if (alone) return eol + 1 == text.size();
    if (!continued) return false;
    for (size_t at = eol + 1; at < text.size();) {
        const size_t end = text.find('\n', at);
        if (text.compare(at, 2, "  ") != 0 || end - at < 3) return false;
        at = end + 1;
    }
    return true;
}

// Absolute, normal, links resolved as far as the path exists.
fs::path resolved_path(const fs::path& path) {
    std::error_code ec;
    const fs::path absolute = fs::absolute(path, ec).lexically_normal();
    const fs::path real = fs::weakly_canonical(absolute, ec);
    return ec ? absolute : real;
}

bool same_file(const struct stat& a, const struct stat& b) {
    return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

// The watergen output directory at or above `path` (not `path` itself), or "".
fs::path output_directory_above(const fs::path& path) {
    for (fs::path dir = path.parent_path(); !dir.empty(); dir = dir.parent_path()) {
        if (is_watergen_manifest_file(dir / "manifest.json")) return dir;
        if (dir == dir.root_path()) break;
    }
    return {};
}

} // namespace

std::optional<std::string> escape_depfile_path(const std::string& path) {
    if (path.empty() || path.find_first_of(kInexpressible) != std::string::npos)
        return std::nullopt;
    std::string out;
    size_t backslashes = 0; // run of backslashes just copied
    for (char c : path) {
        if (c == ' ' || c == '#' || c == ':') {
            // Make and ninja read 2N+1 backslashes and a space (or '#', ':') as N backslashes and
            // the character: a bare ':' would end make's target list.
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
                     "' in a dependency file: make and ninja cannot read back an empty path or "
                     "one with a line break, tab, quote or any of ; | % = * ?";
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

std::string depfile_refusal(const fs::path& file, const std::vector<std::string>& inputs,
                            const fs::path& out) {
    const std::string subject = file.string() + " ";
    struct stat at {};
    const bool exists = ::lstat(file.c_str(), &at) == 0;
    if (!exists && errno != ENOENT) return subject + "cannot be inspected: " + std::strerror(errno);
    const fs::path resolved = resolved_path(file);
    for (const std::string& input : inputs) {
        struct stat in {};
        // The same path, or another name (a hard or symbolic link) of the same file.
        const bool same = resolved_path(input) == resolved ||
                          (exists && ::stat(input.c_str(), &in) == 0 && same_file(at, in));
        if (same)
            return subject + "is the input " + input +
                   "; expected a path of its own for the dependency file";
    }
    const fs::path out_dir = normal_output_path(out);
    const fs::path real_out = resolved_path(out_dir);
    if (path_holds(real_out, resolved))
        return subject + "lies inside the output directory " + out_dir.string() +
               ", which the build replaces; expected a path outside it";
    if (const fs::path above = output_directory_above(resolved); !above.empty())
        return subject + "lies inside " + above.string() +
               ", the output of a watergen build; expected a path outside it";
    if (!exists) return "";
    if (!S_ISREG(at.st_mode))
        return subject + "is " + file_kind(at.st_mode) +
               "; a dependency file replaces only a regular file watergen wrote";
    const SafeRead old = read_regular_file(file, kMaxDepfileBytes);
    if (!old.bytes || !looks_like_our_depfile(*old.bytes))
        return subject + "is a file watergen did not write (not a dependency file naming a "
                         "manifest.json); a dependency file replaces only one watergen wrote";
    return "";
}

std::optional<std::string> write_depfile(const std::string& file, const std::string& target,
                                         const std::vector<std::string>& prerequisites) {
    std::string error;
    const auto text = depfile_text(target, prerequisites, &error);
    if (!text) return file + ": " + error;
    return write_file_atomically(file, *text);
}

} // namespace watergen
