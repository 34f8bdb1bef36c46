#include "watergen/pipeline/file_runs.h"

#include <algorithm>
#include <cstring>

namespace watergen {

namespace {

// A run's record on disk: path length (4 bytes), path, size, digest high and low (8 bytes each).
constexpr size_t kFixedBytes = 4 + 3 * 8;
// Bytes gathered before a write, and read ahead per run while merging.
constexpr size_t kBufferBytes = size_t(1) << 14;

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

SpillFile* FileRuns::file() {
    if (!file_) file_ = std::make_unique<SpillFile>(dir_, ".file-runs");
    return file_->ok() ? file_.get() : nullptr;
}

FileRuns::Run FileRuns::begin_run() {
    Run run(*this);
    SpillFile* f = file();
    run.failed_ = !f;
    run.begin_ = f ? f->end() : 0;
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
    if (!failed_ && !buffer_.empty() && !runs_.file_->append(buffer_)) failed_ = true;
    buffer_.clear();
    if (failed_) return "cannot write the build's file list to its spill file beside the output";
    return std::nullopt;
}

std::optional<std::string> FileRuns::Run::finish() {
    if (auto e = flush()) return e;
    runs_.runs_.push_back({begin_, runs_.file_->end() - begin_});
    return std::nullopt;
}

struct FileRuns::Cursor::State {
    std::vector<RunReader> readers; // source k < readers.size() is a run; the last is `more`
    Next more;
    std::vector<RunRecord> head;
    std::vector<size_t> heap; // sources with a record in `head`, smallest path on top
    bool started = false;
    bool advance(size_t k) {
        return k < readers.size() ? readers[k].next(head[k]) : more && more(head[k]);
    }
    bool later(size_t a, size_t b) const { return head[b].path < head[a].path; }
};

FileRuns::Cursor::Cursor(std::unique_ptr<State> state) : state_(std::move(state)) {}
FileRuns::Cursor::Cursor(Cursor&&) noexcept = default;
FileRuns::Cursor::~Cursor() = default;

bool FileRuns::Cursor::next(RunRecord& r) {
    State& s = *state_;
    auto later = [&](size_t a, size_t b) { return s.later(a, b); };
    if (!s.started) {
        s.started = true;
        for (size_t k = 0; k < s.head.size(); ++k)
            if (s.advance(k)) s.heap.push_back(k);
        std::make_heap(s.heap.begin(), s.heap.end(), later);
    }
    if (s.heap.empty()) return false;
    std::pop_heap(s.heap.begin(), s.heap.end(), later);
    const size_t k = s.heap.back();
    r = s.head[k];
    if (s.advance(k))
        std::push_heap(s.heap.begin(), s.heap.end(), later);
    else
        s.heap.pop_back();
    return true;
}

bool FileRuns::Cursor::failed() const {
    for (const RunReader& r : state_->readers)
        if (r.failed()) return true;
    return false;
}

FileRuns::Cursor FileRuns::cursor(Next more) const {
    auto state = std::make_unique<Cursor::State>();
    for (const SpillFile::Ref& run : runs_)
        state->readers.emplace_back(*file_, run);
    state->more = std::move(more);
    state->head.resize(state->readers.size() + 1);
    return Cursor(std::move(state));
}

bool FileRuns::merged(const Next& more, const std::function<void(const RunRecord&)>& each) const {
    Cursor c = cursor(more);
    for (RunRecord r; c.next(r);)
        each(r);
    return !c.failed();
}

} // namespace watergen
