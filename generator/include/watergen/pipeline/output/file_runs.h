// A file list longer than memory should hold (a build of the whole space writes about 27 files a
// variant, 96 million in all): the staging tree hands over its records a run at a time, sorted by
// path, and they go to a spill file beside the tree; listing them is a k-way merge of the runs
// with what is still in memory, one record at a time.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <xxhash.h>

#include "watergen/pipeline/output/spill_file.h"

namespace watergen {

struct RunRecord {
    std::string path;
    uint64_t size = 0;
    XXH128_hash_t digest{};
};

class FileRuns {
  public:
    // The spill file is made in `dir` at the first run: a list that fits in one run writes
    // nothing (a no-op check beside a read-only cache still works).
    explicit FileRuns(std::filesystem::path dir) : dir_(std::move(dir)) {}
    size_t runs() const { return runs_.size(); }

    // Appends one run; add() must be given paths in ascending order. finish() stores it, or
    // returns why it could not be written.
    class Run {
      public:
        void add(std::string_view path, uint64_t size, XXH128_hash_t digest);
        std::optional<std::string> finish();

      private:
        friend class FileRuns;
        explicit Run(FileRuns& runs) : runs_(runs) {}
        std::optional<std::string> flush();
        FileRuns& runs_;
        std::string buffer_;
        uint64_t begin_ = 0;
        bool failed_ = false;
    };
    Run begin_run();

    // Every record of the runs and of `more` (in path order, false at its end) in path order,
    // one at a time as next() is called.
    using Next = std::function<bool(RunRecord&)>;
    class Cursor {
      public:
        Cursor(Cursor&&) noexcept;
        ~Cursor();
        // The next record; false at the end, or when a run could not be read back (failed()).
        bool next(RunRecord& r);
        bool failed() const;

      private:
        friend class FileRuns;
        struct State;
        explicit Cursor(std::unique_ptr<State> state);
        std::unique_ptr<State> state_;
    };
    Cursor cursor(Next more = {}) const;
    // The same handed to `each`; false when a run could not be read back.
    bool merged(const Next& more, const std::function<void(const RunRecord&)>& each) const;

  private:
    SpillFile* file(); // made on first use; nullptr if it cannot be
    std::filesystem::path dir_;
    std::unique_ptr<SpillFile> file_;
    std::vector<SpillFile::Ref> runs_;
};

} // namespace watergen
