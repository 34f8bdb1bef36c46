#include "watergen/pipeline/output/spill_file.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <string>
#include <unistd.h>

namespace watergen {

SpillFile::SpillFile(const std::filesystem::path& dir, const std::string& name) {
    // Its own name for the moment it has one: two processes may spill into one directory (two
    // builds checking records in one cache).
    static std::atomic<unsigned> made{0};
    const std::filesystem::path path =
        dir / (name + "." + std::to_string(::getpid()) + "." + std::to_string(made++));
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd_ >= 0) ::unlink(path.c_str());
}

SpillFile::~SpillFile() {
    if (fd_ >= 0) ::close(fd_);
}

std::optional<SpillFile::Ref> SpillFile::append(const std::string& bytes) {
    if (fd_ < 0) return std::nullopt;
    const Ref r{end_, bytes.size()};
    for (size_t done = 0; done < bytes.size();) {
        const ssize_t n = ::pwrite(fd_, bytes.data() + done, bytes.size() - done,
                                   static_cast<off_t>(end_ + done));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return std::nullopt;
        done += static_cast<size_t>(n);
    }
    end_ += bytes.size();
    return r;
}

bool SpillFile::read(uint64_t offset, uint64_t size, std::string& out) const {
    out.resize(size);
    size_t done = 0;
    while (done < size) {
        const ssize_t n =
            ::pread(fd_, out.data() + done, size - done, static_cast<off_t>(offset + done));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return false;
        if (n == 0) break;
        done += static_cast<size_t>(n);
    }
    out.resize(done);
    return true;
}

std::string spill_record(std::initializer_list<std::string_view> fields) {
    std::string out;
    for (std::string_view f : fields) {
        const auto size = static_cast<uint32_t>(f.size());
        out.append(reinterpret_cast<const char*>(&size), sizeof size);
        out.append(f);
    }
    return out;
}

bool SpillReader::fill(size_t n) {
    if (buffer_.size() - at_ >= n) return true;
    if (next_ >= end_) return false;
    std::string more;
    const uint64_t want = std::min<uint64_t>(std::max<size_t>(n, size_t(1) << 14), end_ - next_);
    if (!file_->read(next_, want, more) || more.empty()) return failed_ = true, false;
    next_ += more.size();
    buffer_.erase(0, at_);
    at_ = 0;
    buffer_ += more;
    return buffer_.size() >= n || fill(n);
}

bool SpillReader::next(std::vector<std::string>& fields, size_t n) {
    fields.resize(n);
    for (size_t k = 0; k < n; ++k) {
        if (!fill(sizeof(uint32_t))) return failed_ = failed_ || k > 0, false;
        uint32_t size;
        std::memcpy(&size, buffer_.data() + at_, sizeof size);
        if (!fill(sizeof size + size)) return failed_ = true, false;
        fields[k].assign(buffer_.data() + at_ + sizeof size, size);
        at_ += sizeof size + size;
    }
    return true;
}

} // namespace watergen
