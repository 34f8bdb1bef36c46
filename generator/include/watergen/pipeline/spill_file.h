// Scratch space on disk for what a long build or merge would otherwise hold: an unlinked file in
// the staging directory (on the output's file system, gone when closed or when the process dies,
// never part of the tree that is committed). Bytes are appended and read back by offset.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace watergen {

class SpillFile {
  public:
    struct Ref {
        uint64_t offset = 0, size = 0;
    };
    // `name` is the file's name for the moment it has one (it is unlinked at once).
    SpillFile(const std::filesystem::path& dir, const std::string& name);
    ~SpillFile();
    SpillFile(const SpillFile&) = delete;
    SpillFile& operator=(const SpillFile&) = delete;
    bool ok() const { return fd_ >= 0; }
    // Appends `bytes`; nullopt when they cannot be written (a full disk).
    std::optional<Ref> append(const std::string& bytes);
    uint64_t end() const { return end_; }
    // Up to `size` bytes at `offset` into `out` (fewer at the end); false on a read error.
    bool read(uint64_t offset, uint64_t size, std::string& out) const;

  private:
    int fd_ = -1;
    uint64_t end_ = 0;
};

} // namespace watergen
