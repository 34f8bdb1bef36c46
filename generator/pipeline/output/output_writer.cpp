#include "watergen/pipeline/output/output_writer.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <system_error>
#include <unistd.h>
#include <vector>

namespace watergen {

namespace fs = std::filesystem;

namespace {

std::string unique_suffix() {
    return ".tmp-" + std::to_string(::getpid());
}

} // namespace

std::optional<std::string> write_new_file(const fs::path& path, const std::string& data) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0) {
        const int e = errno;
        return "cannot create " + path.string() + ": " + std::strerror(e);
    }
    size_t done = 0;
    while (done < data.size()) {
        const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int e = n < 0 ? errno : ENOSPC;
            ::close(fd);
            return "cannot write " + path.string() + ": " + std::strerror(e);
        }
        done += static_cast<size_t>(n);
    }
    if (::close(fd) != 0) {
        const int e = errno;
        return "cannot write " + path.string() + ": " + std::strerror(e);
    }
    return std::nullopt;
}

bool is_plain_relative_path(const std::string& path) {
    if (path.empty() || path.find('\0') != std::string::npos) return false;
    size_t start = 0;
    for (;;) {
        const size_t slash = path.find('/', start);
        const std::string part =
            path.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
        if (part.empty() || part == "." || part == "..") return false;
        if (slash == std::string::npos) return true;
        start = slash + 1;
    }
}

std::optional<std::string> write_file_atomically(const fs::path& path,
                                                 const std::string& contents) {
    const fs::path tmp = path.string() + unique_suffix();
    std::error_code ec;
    fs::remove(tmp, ec); // left by a killed process of the same pid
    if (auto e = write_new_file(tmp, contents)) {
        fs::remove(tmp, ec); // a short write (a full disk) leaves what it wrote
        return e;
    }
    fs::rename(tmp, path, ec);
    if (ec) {
        std::error_code ignored; // `ec` keeps the rename's error for the message
        fs::remove(tmp, ignored);
        return "cannot rename into " + path.string() + ": " + ec.message();
    }
    return std::nullopt;
}

std::optional<std::string> write_file_atomically(const fs::path& path, const ProduceText& produce) {
    const fs::path tmp = path.string() + unique_suffix();
    std::error_code ec;
    fs::remove(tmp, ec); // left by a killed process of the same pid
    std::FILE* f = std::fopen(tmp.c_str(), "wbx");
    if (!f) {
        const int e = errno;
        return "cannot create " + tmp.string() + ": " + std::strerror(e);
    }
    bool failed = false;
    produce([&](std::string_view piece) {
        failed = failed || std::fwrite(piece.data(), 1, piece.size(), f) != piece.size();
    });
    const int e = errno;
    failed = std::fclose(f) != 0 || failed;
    if (failed) {
        fs::remove(tmp, ec);
        return "cannot write " + tmp.string() + ": " + std::strerror(e);
    }
    fs::rename(tmp, path, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
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
            std::error_code ignored; // `ec` keeps the rename's error for the message
            fs::remove_all(staging, ignored);
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
    if (had_old) remove_replaced_tree(old);
    return std::nullopt;
}

void remove_replaced_tree(const fs::path& old) {
    std::error_code ec;
    fs::remove_all(old, ec);
    if (!ec) return;
    // The new tree is in place; what is left of the old one only takes room, but it stays
    // until someone removes it, so say where it is.
    std::fprintf(stderr,
                 "watergen: warning: cannot remove the replaced %s: %s; remove it by hand\n",
                 old.string().c_str(), ec.message().c_str());
}

std::optional<std::string> write_tree(const fs::path& root,
                                      const std::map<std::string, std::string>& files) {
    for (const auto& [relative, contents] : files)
        if (!is_plain_relative_path(relative))
            return "'" + relative + "' is not a plain relative path inside " + root.string();
    std::error_code ec;
    for (const auto& [relative, contents] : files) {
        const fs::path target = root / relative;
        fs::create_directories(target.parent_path(), ec);
        if (ec) return "cannot create " + target.parent_path().string() + ": " + ec.message();
        if (auto e = write_new_file(target, contents)) return e;
    }
    return std::nullopt;
}

fs::path write_staged_tree(const fs::path& dir, const std::map<std::string, std::string>& files,
                           std::string* error) {
    const fs::path staging = make_staging_directory(dir, error);
    if (staging.empty()) return {};
    if (auto e = write_tree(staging, files)) {
        std::error_code ec;
        fs::remove_all(staging, ec);
        if (error) *error = *e;
        return {};
    }
    return staging;
}

std::optional<std::string>
write_directory_atomically(const fs::path& dir, const std::map<std::string, std::string>& files) {
    std::string error;
    const fs::path staging = write_staged_tree(dir, files, &error);
    if (staging.empty()) return error;
    return commit_directory(staging, dir);
}

// Puts `staging` in the place of `dir` in one step: renameat2(RENAME_EXCHANGE) swaps the two
// names atomically, so whenever the process dies, `dir` holds either the old output or the
// new one, never nothing. Without an old output, a rename that replaces nothing; if a
// concurrent build creates `dir` in between, exchange with that. On file systems that cannot
// exchange, the two-rename commit of output_writer.h.
std::optional<std::string> swap_directory_into_place(const fs::path& staging, const fs::path& dir) {
    for (int attempt = 0; attempt < 3; ++attempt) {
        if (::renameat2(AT_FDCWD, staging.c_str(), AT_FDCWD, dir.c_str(), RENAME_EXCHANGE) == 0) {
            remove_replaced_tree(staging); // the old output, now under the staging name
            return std::nullopt;
        }
        if (errno != ENOENT) break;
        if (::renameat2(AT_FDCWD, staging.c_str(), AT_FDCWD, dir.c_str(), RENAME_NOREPLACE) == 0)
            return std::nullopt;
        if (errno != EEXIST) break;
    }
    return commit_directory(staging, dir);
}

// A killed build leaves its staging directory ("<out>.tmp-<pid>", or "<out>.old.tmp-<pid>"
// from the fallback commit) beside the output; remove those whose process is gone.
fs::path make_unique_directory(const fs::path& root, const std::string& prefix,
                               std::string* error) {
    std::error_code ec;
    fs::create_directories(root, ec);
    std::string name = (root / (prefix + "XXXXXX")).string();
    if (::mkdtemp(name.data())) return name;
    if (error) *error = "cannot create " + name + ": " + std::strerror(errno);
    return {};
}

void remove_stale_staging(const fs::path& out) {
    std::error_code ec;
    const fs::path parent = out.parent_path().empty() ? fs::path(".") : out.parent_path();
    const std::string name = out.filename().string();
    std::vector<fs::path> stale;
    for (const auto& e : fs::directory_iterator(parent, ec)) {
        const std::string entry = e.path().filename().string();
        for (const std::string& prefix : {name + ".tmp-", name + ".old.tmp-"}) {
            if (entry.rfind(prefix, 0) != 0) continue;
            const std::string digits = entry.substr(prefix.size());
            if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos)
                continue;
            const long pid = std::stol(digits);
            if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)
                stale.push_back(e.path());
        }
    }
    for (const auto& p : stale)
        fs::remove_all(p, ec);
}

} // namespace watergen
