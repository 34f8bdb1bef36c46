#include "watergen/pipeline/staged_tree.h"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "watergen/pipeline/build_cache.h"
#include "watergen/pipeline/output_writer.h"
#include "watergen/pipeline/safe_read.h"

namespace watergen {

namespace fs = std::filesystem;

namespace {

// Files a build wrote are a few MB at most; the manifest is read back by no one.
constexpr size_t kMaxReadBackBytes = size_t(64) << 20;

} // namespace

std::unique_ptr<StagedTree> StagedTree::open(const fs::path& out, std::string* error) {
    remove_stale_staging(out);
    const fs::path dir = make_staging_directory(out, error);
    if (dir.empty()) return nullptr;
    return std::unique_ptr<StagedTree>(new StagedTree(dir));
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

void StagedTree::record(const std::string& relative, uint64_t size, XXH128_hash_t digest) {
    std::lock_guard<std::mutex> guard(lock_);
    files_.push_back({paths_.intern(relative), size, digest});
}

std::optional<std::string> StagedTree::write(const std::string& relative,
                                             const std::string& bytes) {
    if (auto e = make_parent(relative)) return e;
    if (auto e = write_new_file(dir_ / relative, bytes)) return e;
    record(relative, bytes.size(), XXH3_128bits(bytes.data(), bytes.size()));
    return std::nullopt;
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
    std::vector<uint32_t> order(files_.size());
    for (size_t i = 0; i < order.size(); ++i)
        order[i] = static_cast<uint32_t>(i);
    std::sort(order.begin(), order.end(),
              [&](uint32_t a, uint32_t b) { return paths_.less(files_[a].path, files_[b].path); });
    RecordedFile f;
    for (const uint32_t i : order) {
        const Entry& e = files_[i];
        f.path = paths_.text(e.path);
        f.size = e.size;
        f.digest = digest_text(e.digest.high64, e.digest.low64);
        each(f);
    }
}

size_t StagedTree::count() const {
    std::lock_guard<std::mutex> guard(lock_);
    return files_.size();
}

std::optional<std::string> StagedTree::commit(const fs::path& out) {
    committed_ = true; // swapped in, or removed by the swap's fallback on failure
    auto e = swap_directory_into_place(dir_, out);
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
    tree_->record(relative_, size_, XXH3_128bits_digest(state_.get()));
    return std::nullopt;
}

} // namespace watergen
