#include "watergen/pipeline/record/staged_tree.h"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "watergen/pipeline/cache/build_cache.h"
#include "watergen/pipeline/output/output_writer.h"
#include "watergen/pipeline/output/safe_read.h"

namespace watergen {

namespace fs = std::filesystem;

namespace {

// Files a build wrote are a few MB at most; the manifest is read back by no one.
constexpr size_t kMaxReadBackBytes = size_t(64) << 20;

} // namespace

std::unique_ptr<StagedTree> StagedTree::open(const fs::path& out, std::string* error,
                                             size_t run_files) {
    remove_stale_staging(out);
    const fs::path dir = make_staging_directory(out, error);
    if (dir.empty()) return nullptr;
    return std::unique_ptr<StagedTree>(new StagedTree(dir, std::max<size_t>(run_files, 1)));
}

StagedTree::~StagedTree() {
    if (committed_) return;
    std::error_code ec;
    fs::remove_all(dir_, ec);
}

std::optional<std::string> StagedTree::make_parent(const std::string& relative) {
    if (!is_plain_relative_path(relative))
        return "'" + relative + "' is not a plain relative path inside " + dir_.string();
    const size_t slash = relative.rfind('/');
    if (slash == std::string::npos) return std::nullopt;
    const std::string parent = relative.substr(0, slash);
    const uint64_t id = XXH64(parent.data(), parent.size(), 0);
    std::lock_guard<std::mutex> guard(lock_);
    if (directories_.count(id)) return std::nullopt;
    std::error_code ec;
    fs::create_directories(dir_ / parent, ec);
    if (ec) return "cannot create " + (dir_ / parent).string() + ": " + ec.message();
    directories_.insert(id);
    return std::nullopt;
}

std::optional<std::string> StagedTree::record(const std::string& relative, uint64_t size,
                                              XXH128_hash_t digest) {
    std::lock_guard<std::mutex> guard(lock_);
    files_.push_back({paths_.intern(relative), size, digest});
    if (files_.size() < run_files_) return std::nullopt;
    return spill();
}

namespace {

// The positions of `files` in path order.
template <typename Entries>
std::vector<uint32_t> path_order(const Entries& files, const PathParts& paths) {
    std::vector<uint32_t> order(files.size());
    for (size_t i = 0; i < order.size(); ++i)
        order[i] = static_cast<uint32_t>(i);
    std::sort(order.begin(), order.end(),
              [&](uint32_t a, uint32_t b) { return paths.less(files[a].path, files[b].path); });
    return order;
}

} // namespace

std::optional<std::string> StagedTree::spill() {
    if (!runs_) runs_ = std::make_unique<FileRuns>(dir_);
    if (!failure_.empty()) return failure_;
    FileRuns::Run run = runs_->begin_run();
    for (const uint32_t i : path_order(files_, paths_))
        run.add(paths_.text(files_[i].path), files_[i].size, files_[i].digest);
    if (auto e = run.finish()) return failure_ = *e;
    spilled_ += files_.size();
    // A run holds its paths as text: the interned parts start again, and so does the memory of
    // the directories made (making one again is harmless).
    std::vector<Entry>().swap(files_);
    paths_ = PathParts();
    directories_.clear();
    return std::nullopt;
}

std::optional<std::string> StagedTree::write(const std::string& relative,
                                             const std::string& bytes) {
    if (auto e = make_parent(relative)) return e;
    if (auto e = write_new_file(dir_ / relative, bytes)) return e;
    return record(relative, bytes.size(), XXH3_128bits(bytes.data(), bytes.size()));
}

StagedStream StagedTree::stream(const std::string& relative) {
    if (auto e = make_parent(relative)) return StagedStream(this, relative, nullptr, *e);
    const fs::path path = dir_ / relative;
    // "x": never through an existing name, as write_new_file.
    std::FILE* f = std::fopen(path.c_str(), "wbx");
    if (!f) {
        const int e = errno;
        return StagedStream(this, relative, nullptr,
                            "cannot create " + path.string() + ": " + std::strerror(e));
    }
    return StagedStream(this, relative, f, "");
}

std::optional<std::string> StagedTree::read(const std::string& relative) const {
    if (!has(relative)) return std::nullopt;
    SafeRead r = read_regular_file(dir_ / relative, kMaxReadBackBytes);
    return std::move(r.bytes);
}

bool StagedTree::has(const std::string& relative) const {
    std::error_code ec;
    return is_plain_relative_path(relative) && fs::is_regular_file(dir_ / relative, ec);
}

void StagedTree::for_each_file(const std::function<void(const RecordedFile&)>& each) const {
    std::lock_guard<std::mutex> guard(lock_);
    const std::vector<uint32_t> order = path_order(files_, paths_);
    RecordedFile f;
    auto give = [&](std::string path, uint64_t size, XXH128_hash_t digest) {
        f.path = std::move(path);
        f.size = size;
        f.digest = digest_text(digest.high64, digest.low64);
        each(f);
    };
    if (!runs_) {
        for (const uint32_t i : order)
            give(paths_.text(files_[i].path), files_[i].size, files_[i].digest);
        return;
    }
    size_t next = 0;
    const FileRuns::Next held = [&](RunRecord& r) {
        if (next == order.size()) return false;
        const Entry& e = files_[order[next++]];
        r.path = paths_.text(e.path);
        r.size = e.size;
        r.digest = e.digest;
        return true;
    };
    if (!runs_->merged(held, [&](const RunRecord& r) { give(r.path, r.size, r.digest); }) &&
        failure_.empty())
        failure_ = "cannot read the build's file list back from its spill file in " + dir_.string();
}

size_t StagedTree::count() const {
    std::lock_guard<std::mutex> guard(lock_);
    return spilled_ + files_.size();
}

std::string StagedTree::failure() const {
    std::lock_guard<std::mutex> guard(lock_);
    return failure_;
}

std::optional<std::string> StagedTree::commit(const fs::path& out) {
    committed_ = true; // swapped in, or removed by the swap's fallback on failure
    std::optional<std::string> e = failure();
    if (e->empty()) e = swap_directory_into_place(dir_, out);
    if (e) {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    return e;
}

StagedStream::StagedStream(StagedTree* tree, std::string relative, std::FILE* file,
                           std::string error)
    : tree_(tree), relative_(std::move(relative)), file_(file), error_(std::move(error)),
      state_(XXH3_createState(), XXH3_freeState) {
    XXH3_128bits_reset(state_.get());
}

StagedStream::StagedStream(StagedStream&& o) noexcept
    : tree_(o.tree_), relative_(std::move(o.relative_)), file_(o.file_),
      error_(std::move(o.error_)), size_(o.size_), state_(std::move(o.state_)) {
    o.file_ = nullptr;
}

StagedStream::~StagedStream() {
    if (file_) std::fclose(file_);
}

void StagedStream::write(std::string_view bytes) {
    if (!file_ || !error_.empty()) return;
    if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) {
        const int e = errno;
        error_ = "cannot write " + (tree_->dir() / relative_).string() + ": " + std::strerror(e);
        return;
    }
    XXH3_128bits_update(state_.get(), bytes.data(), bytes.size());
    size_ += bytes.size();
}

std::optional<std::string> StagedStream::close() {
    if (file_) {
        const int rc = std::fclose(file_);
        const int e = errno;
        file_ = nullptr;
        if (rc != 0 && error_.empty())
            error_ =
                "cannot write " + (tree_->dir() / relative_).string() + ": " + std::strerror(e);
    }
    if (!error_.empty()) return error_;
    return tree_->record(relative_, size_, XXH3_128bits_digest(state_.get()));
}

} // namespace watergen
