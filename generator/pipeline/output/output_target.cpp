#include "watergen/pipeline/output/output_target.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <set>
#include <sys/stat.h>

#include <nlohmann/json.hpp>

#include "watergen/pipeline/output/json_document.h"
#include "watergen/pipeline/output/safe_read.h"
#include "watergen/runtime/manifest_schema.h"

namespace watergen {

namespace fs = std::filesystem;
namespace mk = manifest_schema;

namespace {

constexpr const char* kReplaceable = "a build replaces only a directory watergen wrote (with its "
                                     "manifest.json), an empty directory or a path that "
                                     "does not exist; it was left untouched";

// "out/", "." and ".." name the directory itself: absolute, normal, no trailing separator.
fs::path normal_absolute(const fs::path& out, std::error_code& ec) {
    fs::path p = fs::absolute(out, ec).lexically_normal();
    if (!p.has_filename() && p.has_relative_path()) p = p.parent_path();
    return p;
}

// Whether every entry of `dir` is the first component of a recorded path: the directory holds
// nothing watergen's last build there did not write. (A record that lost its manifest.json line
// still names what that build wrote: refusing it would refuse every build until the record is
// deleted by hand.)
bool only_recorded_entries(const fs::path& dir, const std::vector<std::string>& recorded) {
    std::set<std::string> tops;
    for (const std::string& p : recorded)
        tops.insert(p.substr(0, p.find('/')));
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
        if (!tops.count(it->path().filename().string())) return false;
    return !ec;
}

// Why the existing directory `dir` may not be replaced; "" when it may.
std::string refusal_for_directory(const fs::path& dir, const std::vector<std::string>& recorded) {
    std::error_code ec;
    fs::directory_iterator it(dir, ec);
    if (ec) return "cannot be listed: " + ec.message();
    if (it == fs::directory_iterator()) return ""; // empty
    if (is_watergen_manifest_file(dir / "manifest.json")) return "";
    // A manifest broken (or lost) since: the record of the last build there still shows the
    // directory is watergen's, so it is rebuilt rather than left for the user to remove.
    if (!recorded.empty() && only_recorded_entries(dir, recorded)) return "";
    return std::string("is a directory of files watergen did not write (no manifest.json of a "
                       "watergen build); ") +
           kReplaceable;
}

} // namespace

bool path_holds(const fs::path& outer, const fs::path& inner) {
    return std::mismatch(outer.begin(), outer.end(), inner.begin(), inner.end()).first ==
           outer.end();
}

fs::path normal_output_path(const fs::path& out) {
    std::error_code ec;
    return normal_absolute(out, ec);
}

namespace {

// The first member of the document is "generator": "watergen <version>".
template <class Input> bool starts_as_manifest(Input&& in) {
    bool ours = false;
    JsonDocumentReader reader{{mk::top::kVariants, mk::top::kShaders},
                              [&](const std::string& name, nlohmann::ordered_json&& value) {
                                  if (name != mk::top::kGenerator) return true;
                                  ours = value.is_string() &&
                                         value.get<std::string>().rfind(mk::top::kGeneratorPrefix,
                                                                        0) == 0;
                                  return false;
                              },
                              [](const std::string&, nlohmann::ordered_json&&) { return true; }};
    return read_json_document(std::forward<Input>(in), reader, nullptr) != JsonReadEnd::Malformed &&
           ours;
}

} // namespace

bool is_watergen_manifest(const std::string& bytes) {
    return starts_as_manifest(std::string_view(bytes));
}

bool is_watergen_manifest_file(const fs::path& path) {
    SafeRead seen;
    std::FILE* f = open_regular_stream(path, seen);
    if (!f) return false;
    const bool ours = starts_as_manifest(f);
    std::fclose(f);
    return ours;
}

OutputTarget check_output_target(const fs::path& out, const std::vector<std::string>& recorded) {
    OutputTarget t;
    if (out.empty()) {
        t.error =
            "the output directory is an empty path; expected a directory to create or replace";
        return t;
    }
    std::error_code ec;
    t.path = normal_absolute(out, ec);
    if (ec) {
        t.error = "cannot resolve the output directory: " + ec.message();
        return t;
    }
    // Name the resolved directory where the given path does not show it plainly ("out/", ".",
    // "a/../b").
    const fs::path last = out.filename();
    const bool plain =
        out.lexically_normal() == out && !last.empty() && last != "." && last != "..";
    const std::string subject =
        "the output directory" + (plain ? "" : " (" + t.path.string() + ")");
    // Replacing the current directory (or one above it) would leave the shell in a deleted one.
    std::error_code cwd_ec, real_ec;
    const fs::path cwd = fs::current_path(cwd_ec);
    const fs::path real = fs::weakly_canonical(t.path, real_ec);
    if (!cwd_ec && !real_ec && path_holds(real, cwd)) {
        t.error = subject +
                  " is the current directory or holds it; name one outside the current directory";
        return t;
    }
    struct stat st {};
    if (::lstat(t.path.c_str(), &st) != 0) {
        const int e = errno;
        if (e != ENOENT) t.error = subject + " cannot be inspected: " + std::strerror(e);
        return t;
    }
    if (!S_ISDIR(st.st_mode)) {
        t.error = subject + " is " + file_kind(st.st_mode) + "; " + kReplaceable;
        return t;
    }
    if (std::string why = refusal_for_directory(t.path, recorded); !why.empty())
        t.error = subject + " " + why;
    return t;
}

} // namespace watergen
