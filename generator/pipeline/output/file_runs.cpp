#include "watergen/pipeline/output/file_runs.h"

#include <algorithm>
#include <cstring>

namespace watergen {

namespace {

// A run's record on disk: a spill record (spill_file.h) of the path and 24 bytes: size, digest
// high and low.
constexpr size_t kFixedBytes = 3 * 8;
// Bytes gathered before a write.
constexpr size_t kBufferBytes = size_t(1) << 14;

// Reads one run back a buffer at a time.
class RunReader {
  public:
    RunReader(const SpillFile& file, SpillFile::Ref run)
        : reader_(file, run.offset, run.offset + run.size) {}
    // The next record into `r`; false at the run's end or on a read error (failed()).
    bool next(RunRecord& r) {
        if (!reader_.next(fields_, 2)) return false;
        if (fields_[1].size() != kFixedBytes) return failed_ = true, false;
        r.path = std::move(fields_[0]);
        std::memcpy(&r.size, fields_[1].data(), 8);
        std::memcpy(&r.digest.high64, fields_[1].data() + 8, 8);
        std::memcpy(&r.digest.low64, fields_[1].data() + 16, 8);
        return true;
    }
    bool failed() const { return failed_ || reader_.failed(); }

  private:
    SpillReader reader_;
    std::vector<std::string> fields_;
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
    char fixed[kFixedBytes];
    std::memcpy(fixed, &size, 8);
    std::memcpy(fixed + 8, &digest.high64, 8);
    std::memcpy(fixed + 16, &digest.low64, 8);
    buffer_ += spill_record({path, std::string_view(fixed, kFixedBytes)});
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
