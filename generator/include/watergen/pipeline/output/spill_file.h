// Scratch space on disk for what a long build or merge would otherwise hold: an unlinked file in
// the staging directory (on the output's file system, gone when closed or when the process dies,
// never part of the tree that is committed). Bytes are appended and read back by offset.
#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

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

// A record of fields (each length-prefixed) to append to a SpillFile.
std::string spill_record(std::initializer_list<std::string_view> fields);

// Reads records of a SpillFile back in order, [begin, end), a buffer at a time.
class SpillReader {
  public:
    SpillReader(const SpillFile& file, uint64_t begin, uint64_t end)
        : file_(&file), next_(begin), end_(end) {}
    // The next record, which must have `n` fields; false at the end, or if it cannot be read
    // (failed()).
    bool next(std::vector<std::string>& fields, size_t n);
    bool failed() const { return failed_; }

  private:
    bool fill(size_t n); // at least n unread bytes buffered
    const SpillFile* file_;
    uint64_t next_, end_;
    std::string buffer_;
    size_t at_ = 0;
    bool failed_ = false;
};

} // namespace watergen
