#include "watergen/eval/measure/scratch_directory.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
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

ScratchDirectory::ScratchDirectory(const fs::path& root, const std::string& prefix)
    : slot_(kSlots) {
    static std::atomic<unsigned> made{0};
    install_handlers();
    sweep_stale_scratch(root, prefix);
    path_ = root / (prefix + std::to_string(::getpid()) + "-" + std::to_string(made++));
    std::error_code ec;
    fs::remove_all(path_, ec);
    slot_ = take_slot(path_); // before it exists: a signal from now on removes it
    fs::create_directories(path_, ec);
    if (ec) error_ = "cannot create " + path_.string() + ": " + ec.message();
}

ScratchDirectory::~ScratchDirectory() {
    std::error_code ec;
    fs::remove_all(path_, ec);
    if (slot_ < kSlots) g_slots[slot_].state.store(0);
}

size_t sweep_stale_scratch(const fs::path& root, const std::string& prefix) {
    size_t removed = 0;
    std::error_code ec;
    for (fs::directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.rfind(prefix, 0) != 0) continue;
        const std::string rest = name.substr(prefix.size());
        const size_t dash = rest.find('-');
        if (dash == 0 || dash == std::string::npos ||
            rest.substr(0, dash).find_first_not_of("0123456789") != std::string::npos)
            continue;
        const pid_t pid = static_cast<pid_t>(std::stol(rest.substr(0, dash)));
        // Gone (ESRCH): nobody will remove it. Alive, or not ours to ask (EPERM): left alone.
        if (::kill(pid, 0) == 0 || errno != ESRCH) continue;
        std::error_code remove_error;
        if (fs::remove_all(it->path(), remove_error) > 0 && !remove_error) ++removed;
    }
    return removed;
}

} // namespace watergen
