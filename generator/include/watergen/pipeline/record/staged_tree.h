// The output of a build as it is made: each file goes to a staging directory beside the output
// as soon as it exists, so memory holds the files in flight, not the whole output. The tree
// keeps what it wrote (path, size, digest) for the build record and shard.json, in 32 bytes a
// file (each job directory's name once) up to a run's worth, then sorted into a spill file beside
// it (file_runs.h): memory holds one run, whatever the build's size. It reads a file back for the
// steps that need one again (the manifest's reflection, frozen modules).
// Until commit() swaps it into place the output is untouched; a tree never committed is removed.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

#include <xxhash.h>

#include "watergen/pipeline/output/file_runs.h"
#include "watergen/pipeline/output/path_parts.h"
#include "watergen/pipeline/record/build_record.h"

namespace watergen {

class StagedTree;

// A file written piece by piece (the manifest), hashed on the way; close() records it.
class StagedStream {
  public:
    StagedStream(StagedStream&&) noexcept;
    ~StagedStream();
    void write(std::string_view bytes);
    // Closes and records the file; the first error of any write, or of the close.
    std::optional<std::string> close();

  private:
    friend class StagedTree;
    StagedStream(StagedTree* tree, std::string relative, std::FILE* file, std::string error);
    StagedTree* tree_;
    std::string relative_;
    std::FILE* file_;
    std::string error_;
    uint64_t size_ = 0;
    std::unique_ptr<XXH3_state_t, XXH_errorcode (*)(XXH3_state_t*)> state_;
};

class StagedTree {
  public:
    // A fresh staging directory beside `out` (make_staging_directory, output_writer.h); nullptr
    // and the error in `error` when it cannot be made.
    // `run_files`: records held before they go to the spill file as one sorted run.
    static constexpr size_t kRunFiles = size_t(1) << 16; // 2 MB of records, 2,400 variants' files
    static std::unique_ptr<StagedTree> open(const std::filesystem::path& out, std::string* error,
                                            size_t run_files = kRunFiles);
    ~StagedTree(); // removes the staging directory unless committed
    StagedTree(const StagedTree&) = delete;
    StagedTree& operator=(const StagedTree&) = delete;

    // Writes one file (a plain relative path, never an existing name); thread-safe.
    std::optional<std::string> write(const std::string& relative, const std::string& bytes);
    StagedStream stream(const std::string& relative);
    // A file written before, read back; nullopt if it was not written or cannot be read.
    std::optional<std::string> read(const std::string& relative) const;
    bool has(const std::string& relative) const;

    // Every file written, sorted by path, one at a time. A spilled run that cannot be read back
    // ends the list early and fails the tree (failure()).
    void for_each_file(const std::function<void(const RecordedFile&)>& each) const;
    size_t count() const;
    // Why the tree cannot be committed (its file list could not be spilled or read back); "" if
    // it can.
    std::string failure() const;
    const std::filesystem::path& dir() const { return dir_; }

    // Puts the tree in place of `out` in one step (renameat2 exchange where the file system
    // has it); the old output stays whole until then. The tree is gone from its staging name
    // either way.
    std::optional<std::string> commit(const std::filesystem::path& out);

  private:
    friend class StagedStream;
    StagedTree(std::filesystem::path dir, size_t run_files)
        : dir_(std::move(dir)), run_files_(run_files) {}
    std::optional<std::string> make_parent(const std::string& relative);
    std::optional<std::string> record(const std::string& relative, uint64_t size,
                                      XXH128_hash_t digest);
    std::optional<std::string> spill(); // with lock_ held

    // A file as the tree keeps it.
    struct Entry {
        PathParts::Path path;
        uint64_t size;
        XXH128_hash_t digest;
    };

    std::filesystem::path dir_;
    mutable std::mutex lock_;
    std::unordered_set<uint64_t> directories_; // made already (XXH64 of the path)
    PathParts paths_;
    std::vector<Entry> files_; // in write order, since the last run
    size_t run_files_;
    std::unique_ptr<FileRuns> runs_; // made at the first run
    size_t spilled_ = 0;             // records in runs_
    mutable std::string failure_;
    bool committed_ = false;
};

} // namespace watergen
