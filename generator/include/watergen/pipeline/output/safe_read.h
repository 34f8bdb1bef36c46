// Reads a file that someone else may have replaced with something hostile (a cache entry, the
// manifest of an earlier output): only a regular file is read, a symbolic link is never
// followed, a FIFO or device is never opened for reading (so nothing blocks or streams forever),
// and nothing larger than a bound is read.
#pragma once

#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <sys/types.h>

namespace watergen {

struct SafeRead {
    std::optional<std::string> bytes; // the whole file, when it passed every check
    bool missing = false;             // nothing at the path (ENOENT): a miss, not damage
    std::string why;  // why it was not read, with the errno text where a call failed
    dev_t device = 0; // of what lstat found, so a caller may remove exactly that
    ino_t inode = 0;
};

// "a regular file", "a symbolic link", "a FIFO", "a character device", ... (for messages).
const char* file_kind(mode_t mode);

SafeRead read_regular_file(const std::filesystem::path& path, size_t max_bytes);
// The same checks, for a file too large to hold (a manifest of many variants): the open stream
// (close it with fclose), or nullptr and why in `r` (its `bytes` stay empty).
std::FILE* open_regular_stream(const std::filesystem::path& path, SafeRead& r);

// Removes what read_regular_file found at `path` (the link itself for a symbolic link), unless
// something else has been put there since: a concurrent writer's fresh file stays.
void remove_if_same(const std::filesystem::path& path, const SafeRead& seen);

} // namespace watergen
