#include "watergen/eval/measure/scratch_directory.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/file.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <mutex>

#include "watergen/toolchain/child_process.h"

namespace watergen {

namespace fs = std::filesystem;

namespace {

// The directories that exist now, for the signal handler: fixed slots it can read without a
// lock or an allocation. `state` 0: free; 1: being filled; 2: holds a path.
constexpr size_t kSlots = 256;
constexpr size_t kPathMax = 1024;
struct Slot {
    std::atomic<int> state{0};
    char path[kPathMax];
};
std::array<Slot, kSlots> g_slots;

size_t take_slot(const fs::path& path) {
    const std::string text = path.string();
    if (text.size() >= kPathMax) return kSlots;
    for (size_t i = 0; i < kSlots; ++i) {
        int free = 0;
        if (!g_slots[i].state.compare_exchange_strong(free, 1)) continue;
        std::memcpy(g_slots[i].path, text.c_str(), text.size() + 1);
        g_slots[i].state.store(2);
        return i;
    }
    return kSlots;
}

// A flat directory and its files, with system calls only (async-signal-safe): the workers'
// scratch holds files, no subdirectories.
void remove_flat_directory(const char* path) {
    const int dir = ::open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir >= 0) {
        alignas(8) char buffer[4096];
        for (;;) {
            const long n = ::syscall(SYS_getdents64, dir, buffer, sizeof buffer);
            if (n <= 0) break;
            for (long at = 0; at < n;) {
                struct Entry {
                    uint64_t ino;
                    int64_t off;
                    unsigned short reclen;
                    unsigned char type;
                    char name[1];
                };
                const auto* e = reinterpret_cast<const Entry*>(buffer + at);
                const bool dots = e->name[0] == '.' &&
                                  (e->name[1] == '\0' || (e->name[1] == '.' && e->name[2] == '\0'));
                if (!dots) ::unlinkat(dir, e->name, 0);
                at += e->reclen;
            }
        }
        ::close(dir);
    }
    ::rmdir(path);
}

void on_signal(int sig) {
    kill_child_processes();
    wait_for_killed_children();
    for (Slot& s : g_slots)
        if (s.state.load() == 2) remove_flat_directory(s.path);
    // End as the signal would have: the default action, raised again.
    ::signal(sig, SIG_DFL);
    ::raise(sig);
}

void install_handlers() {
    static std::once_flag once;
    std::call_once(once, [] {
        struct sigaction action {};
        action.sa_handler = on_signal;
        sigemptyset(&action.sa_mask);
        for (int sig : {SIGINT, SIGTERM, SIGHUP})
            sigaddset(&action.sa_mask, sig);
        for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
            struct sigaction old {};
            // A signal this process ignores (nohup) stays ignored.
            if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
            ::sigaction(sig, &action, nullptr);
        }
    });
}

} // namespace

namespace {

constexpr const char* kLockFile = ".lock";

// <root>/<prefix>XXXXXX, locked from the moment it has that name: made by mkdtemp under a
// hidden name, its lock file taken, then renamed (the lock is on the file, which the rename
// keeps), so a sweep never sees one of ours unlocked while we live. Returns the lock's file
// descriptor (-1 and `error` when it cannot be made) and sets `made`.
int make_locked_directory(const fs::path& root, const std::string& prefix, fs::path& made,
                          size_t& slot, std::string& error) {
    std::error_code ec;
    fs::create_directories(root, ec);
    for (int attempt = 0; attempt < 16; ++attempt) {
        std::string hidden = (root / ("." + prefix + "XXXXXX")).string();
        if (!::mkdtemp(hidden.data())) {
            error = "cannot create " + (root / prefix).string() + "XXXXXX: " + std::strerror(errno);
            return -1;
        }
        const std::string suffix = hidden.substr(hidden.size() - 6);
        const fs::path lock_path = fs::path(hidden) / kLockFile;
        const int fd = ::open(lock_path.c_str(), O_CREAT | O_EXCL | O_RDWR | O_CLOEXEC, 0600);
        if (fd < 0 || ::flock(fd, LOCK_EX) != 0) {
            error = "cannot lock " + lock_path.string() + ": " + std::strerror(errno);
            if (fd >= 0) ::close(fd);
            fs::remove_all(hidden, ec);
            return -1;
        }
        made = root / (prefix + suffix);
        slot = take_slot(made); // before it has the name: a signal from now on removes it
        if (::renameat2(AT_FDCWD, hidden.c_str(), AT_FDCWD, made.c_str(), RENAME_NOREPLACE) == 0)
            return fd;
        const int why = errno;
        if (slot < kSlots) g_slots[slot].state.store(0);
        slot = kSlots;
        fs::remove_all(hidden, ec);
        ::close(fd);
        if (why != EEXIST) {
            error = "cannot create " + made.string() + ": " + std::strerror(why);
            return -1;
        }
    }
    error = "cannot create " + (root / prefix).string() + "XXXXXX: every name tried exists";
    return -1;
}

} // namespace

ScratchDirectory::ScratchDirectory(const fs::path& root, const std::string& prefix)
    : slot_(kSlots) {
    install_handlers();
    sweep_stale_scratch(root, prefix);
    lock_ = make_locked_directory(root, prefix, path_, slot_, error_);
}

ScratchDirectory::~ScratchDirectory() {
    std::error_code ec;
    if (lock_ >= 0) {
        fs::remove_all(path_, ec); // while it is locked: no sweep takes it meanwhile
        ::close(lock_);
    }
    if (slot_ < kSlots) g_slots[slot_].state.store(0);
}

size_t sweep_stale_scratch(const fs::path& root, const std::string& prefix) {
    size_t removed = 0;
    std::error_code ec;
    for (fs::directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.rfind(prefix, 0) != 0) continue;
        // Alive while its process (in whatever PID namespace) holds the lock; a directory with
        // no lock file is not one of ours to judge.
        const int fd = ::open((it->path() / kLockFile).c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0) continue;
        if (::flock(fd, LOCK_EX | LOCK_NB) == 0) {
            std::error_code remove_error;
            if (fs::remove_all(it->path(), remove_error) > 0 && !remove_error) ++removed;
        }
        ::close(fd);
    }
    return removed;
}

} // namespace watergen
