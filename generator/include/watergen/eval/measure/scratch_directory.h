// The scratch directory of one counting worker (draw_count.h): made on construction, removed
// with everything in it on destruction, so that every way out of a count (its end, an error, a
// worker that died) leaves nothing behind. While any exists, SIGINT, SIGTERM and SIGHUP to this
// process kill the running workers (run_child_process's children), remove every scratch
// directory still there, and then end the process as the signal would have. (A SIGKILL cannot
// be caught: the next count sweeps the directories no process holds.) Each directory's
// liveness is a lock its process holds (flock on its .lock file), not a PID: a PID names
// another process, or none, in another PID namespace sharing the same /tmp.
#pragma once

#include <filesystem>
#include <string>

namespace watergen {

class ScratchDirectory {
  public:
    // <root>/<prefix>XXXXXX (mkdtemp's name), locked while this object lives; error() says
    // why not.
    ScratchDirectory(const std::filesystem::path& root, const std::string& prefix);
    ~ScratchDirectory();
    ScratchDirectory(const ScratchDirectory&) = delete;
    ScratchDirectory& operator=(const ScratchDirectory&) = delete;

    const std::filesystem::path& path() const { return path_; }
    const std::string& error() const { return error_; }

  private:
    std::filesystem::path path_;
    std::string error_;
    size_t slot_;
    int lock_ = -1; // the .lock file's descriptor, flock'ed
};

// Removes <root>/<prefix>* whose lock no process holds (left by a process that was killed
// outright); returns how many went. A directory without a lock file is left alone.
size_t sweep_stale_scratch(const std::filesystem::path& root, const std::string& prefix);

} // namespace watergen
