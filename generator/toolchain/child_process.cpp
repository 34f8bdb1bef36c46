#include "watergen/toolchain/child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>

extern char** environ;

namespace watergen {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    constexpr size_t kMax = 8000; // enough to see the errors, not a whole disassembly
    if (text.size() > kMax) text = text.substr(0, kMax) + "\n[...]";
    return text;
}

// The children running now, for kill_child_processes (a signal handler reads it: plain atomics,
// no lock). A slot is 0 when free.
constexpr size_t kMaxChildren = 256;
std::atomic<pid_t> g_children[kMaxChildren];

size_t remember_child(pid_t pid) {
    for (size_t i = 0; i < kMaxChildren; ++i) {
        pid_t free = 0;
        if (g_children[i].compare_exchange_strong(free, pid)) return i;
    }
    return kMaxChildren; // table full: the child still dies with this process (PDEATHSIG)
}

// argv[0] as execve needs it: itself when it names a path, else the first PATH entry that
// holds an executable of that name (found before fork: the child may only make
// async-signal-safe calls).
std::string resolve_program(const std::string& name) {
    if (name.find('/') != std::string::npos) return name;
    const char* path = std::getenv("PATH");
    std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
    size_t start = 0;
    while (start <= dirs.size()) {
        const size_t end = std::min(dirs.find(':', start), dirs.size());
        const std::string dir = dirs.substr(start, end - start);
        const std::string candidate = (dir.empty() ? "." : dir) + "/" + name;
        if (::access(candidate.c_str(), X_OK) == 0) return candidate;
        start = end + 1;
    }
    return "";
}

} // namespace

void kill_child_processes() {
    for (auto& slot : g_children)
        if (const pid_t pid = slot.load(); pid > 0) ::kill(pid, SIGKILL);
}

void wait_for_killed_children() {
    for (auto& slot : g_children)
        if (const pid_t pid = slot.load(); pid > 0) {
            siginfo_t info;
            // WNOWAIT: the thread that started it still reaps it.
            while (::waitid(P_PID, id_t(pid), &info, WEXITED | WNOWAIT) < 0 && errno == EINTR) {
            }
        }
}

std::string run_child_process(const std::vector<std::string>& argv, const fs::path& dir,
                              const std::vector<std::string>& env) {
    const std::string name = fs::path(argv[0]).filename().string();
    const fs::path out_path = dir / (name + ".stdout");
    const fs::path err_path = dir / (name + ".stderr");
    std::vector<char*> args;
    for (const auto& a : argv)
        args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    // This environment minus the variables `env` names, then those `env` sets.
    const auto name_of = [](std::string_view entry) { return entry.substr(0, entry.find('=')); };
    std::vector<char*> envp;
    for (char** e = environ; *e; ++e) {
        bool named = false;
        for (const auto& set : env)
            named = named || name_of(*e) == name_of(set);
        if (!named) envp.push_back(*e);
    }
    for (const auto& set : env)
        if (set.find('=') != std::string::npos) envp.push_back(const_cast<char*>(set.c_str()));
    envp.push_back(nullptr);
    const std::string program = resolve_program(argv[0]);
    if (program.empty()) return argv[0] + ": cannot start: " + std::strerror(ENOENT);
    const pid_t parent = ::getpid();
    int ready[2]; // closed on exec; the child writes errno there when it cannot start
    if (::pipe2(ready, O_CLOEXEC) != 0)
        return argv[0] + ": cannot start: pipe: " + std::strerror(errno);

    const pid_t pid = ::fork();
    if (pid < 0) {
        const int e = errno;
        ::close(ready[0]);
        ::close(ready[1]);
        return argv[0] + ": cannot start: fork: " + std::strerror(e);
    }
    if (pid == 0) {
        // The child dies with this process however it ends (a kill, a crash): a counting
        // worker spins at full CPU for minutes otherwise, adopted by init. If the parent died
        // before the prctl took effect, getppid no longer names it.
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != parent) ::_exit(127);
        sigset_t none;
        sigemptyset(&none);
        ::sigprocmask(SIG_SETMASK, &none, nullptr);
        const int in = ::open("/dev/null", O_RDONLY);
        const int out = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (in >= 0 && out >= 0 && err >= 0 && ::dup2(in, STDIN_FILENO) >= 0 &&
            ::dup2(out, STDOUT_FILENO) >= 0 && ::dup2(err, STDERR_FILENO) >= 0)
            ::execve(program.c_str(), args.data(), envp.data());
        const int e = errno;
        [[maybe_unused]] const ssize_t n = ::write(ready[1], &e, sizeof e);
        ::_exit(127);
    }
    const size_t slot = remember_child(pid);
    ::close(ready[1]);
    int start_error = 0;
    ssize_t got;
    while ((got = ::read(ready[0], &start_error, sizeof start_error)) < 0 && errno == EINTR) {
    }
    ::close(ready[0]);

    int status = 0;
    std::string failure;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) {
            failure = argv[0] + ": waitpid failed: " + std::strerror(errno);
            break;
        }
    if (slot < kMaxChildren) g_children[slot].store(0);
    if (!failure.empty()) return failure;
    if (got == sizeof start_error) return argv[0] + ": cannot start: " + std::strerror(start_error);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return {};

    std::string why = WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                        : "killed by signal " + std::to_string(WTERMSIG(status));
    std::string output = read_text(err_path);
    if (output.find_first_not_of(" \t\r\n") == std::string::npos) output = read_text(out_path);
    return argv[0] + ": " + why + "\n" + output;
}

} // namespace watergen
