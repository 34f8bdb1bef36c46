#include "watergen/pipeline/file_runs.h"

#include <cstring>
#include <queue>

namespace watergen {

namespace {

// A run's record on disk: path length (4 bytes), path, size, digest high and low (8 bytes each).
constexpr size_t kFixedBytes = 4 + 3 * 8;
// Bytes gathered before a write, and read ahead per run while merging.
constexpr size_t kBufferBytes = size_t(1) << 16;

template <typename T> void put(std::string& out, T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out.append(bytes, sizeof(T));
}

template <typename T> T get(const char* at) {
    T value;
    std::memcpy(&value, at, sizeof(T));
    return value;
}

// Reads one run back a buffer at a time.
class RunReader {
  public:
    RunReader(const SpillFile& file, SpillFile::Ref run)
        : file_(file), next_(run.offset), end_(run.offset + run.size) {}
    // The next record into `r`; false at the run's end or on a read error (failed()).
    bool next(RunRecord& r) {
        if (!fill(kFixedBytes)) return false;
        const auto length = get<uint32_t>(buffer_.data() + at_);
        if (!fill(kFixedBytes + length)) return failed_ = true, false;
        const char* p = buffer_.data() + at_ + 4;
        r.path.assign(p, length);
        p += length;
        r.size = get<uint64_t>(p);
        r.digest.high64 = get<uint64_t>(p + 8);
        r.digest.low64 = get<uint64_t>(p + 16);
        at_ += kFixedBytes + length;
        return true;
    }
    bool failed() const { return failed_; }

  private:
    // At least `n` unread bytes in the buffer; false at the run's end (or on an error).
    bool fill(size_t n) {
        if (buffer_.size() - at_ >= n) return true;
        if (next_ >= end_) return false;
        std::string more;
        if (!file_.read(next_, std::min<uint64_t>(std::max(n, kBufferBytes), end_ - next_), more) ||
            more.empty())
            return failed_ = true, false;
        next_ += more.size();
        buffer_.erase(0, at_);
        at_ = 0;
        buffer_ += more;
        return buffer_.size() >= n || fill(n);
    }
    const SpillFile& file_;
    uint64_t next_, end_;
    std::string buffer_;
    size_t at_ = 0;
    bool failed_ = false;
};

} // namespace

FileRuns::Run FileRuns::begin_run() {
    Run run(*this);
    run.begin_ = file_.end();
    return run;
}

void FileRuns::Run::add(std::string_view path, uint64_t size, XXH128_hash_t digest) {
    put(buffer_, static_cast<uint32_t>(path.size()));
    buffer_.append(path);
    put(buffer_, size);
    put(buffer_, digest.high64);
    put(buffer_, digest.low64);
    if (buffer_.size() >= kBufferBytes) flush();
}

std::optional<std::string> FileRuns::Run::flush() {
    if (!failed_ && !buffer_.empty() && !runs_.file_.append(buffer_)) failed_ = true;
    buffer_.clear();
    if (failed_) return "cannot write the build's file list to its spill file beside the output";
    return std::nullopt;
}

std::optional<std::string> FileRuns::Run::finish() {
    if (auto e = flush()) return e;
    runs_.runs_.push_back({begin_, runs_.file_.end() - begin_});
    return std::nullopt;
}

bool FileRuns::merged(const Next& more, const std::function<void(const RunRecord&)>& each) const {
    std::vector<RunReader> readers;
    for (const SpillFile::Ref& run : runs_)
        readers.emplace_back(file_, run);
    // Source k < readers.size() is a run; the last is `more`.
    const size_t sources = readers.size() + 1;
    std::vector<RunRecord> head(sources);
    auto advance = [&](size_t k) {
        return k < readers.size() ? readers[k].next(head[k]) : more(head[k]);
    };
    auto later = [&](size_t a, size_t b) { return head[b].path < head[a].path; };
    std::priority_queue<size_t, std::vector<size_t>, decltype(later)> queue(later);
    for (size_t k = 0; k < sources; ++k)
        if (advance(k)) queue.push(k);
    while (!queue.empty()) {
        const size_t k = queue.top();
        queue.pop();
        each(head[k]);
        if (advance(k)) queue.push(k);
    }
    for (const RunReader& r : readers)
        if (r.failed()) return false;
    return true;
}

} // namespace watergen
