#include "watergen/pipeline/output_writer.h"

#include <fstream>
#include <system_error>
#include <unistd.h>

namespace watergen {

namespace fs = std::filesystem;

namespace {

std::optional<std::string> write_plain(const fs::path& path, const std::string& contents) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) return "cannot open " + path.string() + " for writing";
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    out.close();
    if (!out) return "cannot write " + path.string();
    return std::nullopt;
}

std::string unique_suffix() { return ".tmp-" + std::to_string(::getpid()); }

} // namespace

std::optional<std::string> write_file_atomically(const fs::path& path, const std::string& contents) {
    const fs::path tmp = path.string() + unique_suffix();
    if (auto e = write_plain(tmp, contents)) return e;
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        return "cannot rename into " + path.string() + ": " + ec.message();
    }
    return std::nullopt;
}

fs::path make_staging_directory(const fs::path& dir, std::string* error) {
    std::error_code ec;
    const fs::path parent = dir.parent_path().empty() ? fs::path(".") : dir.parent_path();
    fs::create_directories(parent, ec);
    if (ec) {
        if (error) *error = "cannot create " + parent.string() + ": " + ec.message();
        return {};
    }
    const fs::path staging = dir.string() + unique_suffix();
    fs::remove_all(staging, ec);
    fs::create_directories(staging, ec);
    if (ec) {
        if (error) *error = "cannot create " + staging.string() + ": " + ec.message();
        return {};
    }
    return staging;
}

std::optional<std::string> commit_directory(const fs::path& staging, const fs::path& dir) {
    std::error_code ec;
    const fs::path old = dir.string() + ".old" + unique_suffix();
    const bool had_old = fs::exists(dir);
    if (had_old) {
        fs::rename(dir, old, ec);
        if (ec) {
            fs::remove_all(staging, ec);
            return "cannot move aside " + dir.string() + ": " + ec.message();
        }
    }
    fs::rename(staging, dir, ec);
    if (ec) {
        std::error_code ignored;
        if (had_old) fs::rename(old, dir, ignored);
        fs::remove_all(staging, ignored);
        return "cannot rename into " + dir.string() + ": " + ec.message();
    }
    if (had_old) fs::remove_all(old, ec);
    return std::nullopt;
}

std::optional<std::string> write_directory_atomically(const fs::path& dir, const std::map<std::string, std::string>& files) {
    std::string error;
    const fs::path staging = make_staging_directory(dir, &error);
    if (staging.empty()) return error;
    std::error_code ec;
    for (const auto& [relative, contents] : files) {
        const fs::path target = staging / relative;
        fs::create_directories(target.parent_path(), ec);
        if (ec) {
            fs::remove_all(staging, ec);
            return "cannot create " + target.parent_path().string();
        }
        if (auto e = write_plain(target, contents)) {
            fs::remove_all(staging, ec);
            return e;
        }
    }
    return commit_directory(staging, dir);
}

} // namespace watergen
