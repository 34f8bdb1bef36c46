#include "watergen/pipeline/output/safe_read.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace watergen {

namespace {

std::string errno_text(int e) {
    return std::strerror(e);
}

// Reads at most max_bytes + 1 bytes, so a file that grew past the bound is noticed.
std::optional<std::string> read_bounded(int fd, size_t max_bytes, std::string& why) {
    std::string bytes;
    char buffer[1 << 16];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0) {
            const int e = errno;
            if (e == EINTR) continue;
            why = "cannot read: " + errno_text(e);
            return std::nullopt;
        }
        if (n == 0) return bytes;
        bytes.append(buffer, static_cast<size_t>(n));
        if (bytes.size() > max_bytes) {
            why = "larger than " + std::to_string(max_bytes) + " bytes";
            return std::nullopt;
        }
    }
}

} // namespace

const char* file_kind(mode_t mode) {
    if (S_ISREG(mode)) return "a regular file";
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISLNK(mode)) return "a symbolic link";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "an unknown kind of file";
}

namespace {

// Opens `path` for reading if it is a regular file of at most max_bytes; -1 and why in `r`.
int open_regular(const std::filesystem::path& path, size_t max_bytes, SafeRead& r) {
    struct stat seen {};
    if (::lstat(path.c_str(), &seen) != 0) {
        const int e = errno;
        r.missing = e == ENOENT;
        r.why = "cannot inspect: " + errno_text(e);
        return -1;
    }
    r.device = seen.st_dev;
    r.inode = seen.st_ino;
    if (!S_ISREG(seen.st_mode)) {
        r.why = std::string("is ") + file_kind(seen.st_mode) + ", not a regular file";
        return -1;
    }
    if (static_cast<unsigned long long>(seen.st_size) > max_bytes) {
        r.why =
            "is " + std::to_string(seen.st_size) + " bytes, more than " + std::to_string(max_bytes);
        return -1;
    }
    // O_NOFOLLOW and O_NONBLOCK: whatever was swapped in since the lstat, opening it neither
    // follows a link nor waits for a FIFO's writer; fstat then checks what was opened.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        const int e = errno;
        r.why = "cannot open: " + errno_text(e);
        return -1;
    }
    struct stat opened {};
    if (::fstat(fd, &opened) != 0) {
        const int e = errno;
        r.why = "cannot inspect: " + errno_text(e);
    } else if (!S_ISREG(opened.st_mode) || opened.st_dev != seen.st_dev ||
               opened.st_ino != seen.st_ino) {
        r.why = "was replaced while being opened";
    } else {
        return fd;
    }
    ::close(fd);
    return -1;
}

} // namespace

SafeRead read_regular_file(const std::filesystem::path& path, size_t max_bytes) {
    SafeRead r;
    const int fd = open_regular(path, max_bytes, r);
    if (fd < 0) return r;
    r.bytes = read_bounded(fd, max_bytes, r.why);
    ::close(fd);
    return r;
}

std::FILE* open_regular_stream(const std::filesystem::path& path, SafeRead& r) {
    const int fd = open_regular(path, static_cast<size_t>(-1), r);
    if (fd < 0) return nullptr;
    std::FILE* f = ::fdopen(fd, "rb");
    if (!f) {
        const int e = errno;
        r.why = "cannot open: " + errno_text(e);
        ::close(fd);
    }
    return f;
}

void remove_if_same(const std::filesystem::path& path, const SafeRead& seen) {
    struct stat now {};
    if (seen.missing || ::lstat(path.c_str(), &now) != 0) return;
    if (now.st_dev != seen.device || now.st_ino != seen.inode || S_ISDIR(now.st_mode)) return;
    ::unlink(path.c_str());
}

} // namespace watergen
