#include "watergen/pipeline/spill_file.h"

#include <atomic>
#include <cerrno>
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

} // namespace watergen
