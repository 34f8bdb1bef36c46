// The scratch directory of one counting worker (draw_count.h): made on construction, removed
// with everything in it on destruction, so that every way out of a count (its end, an error, a
// worker that died) leaves nothing behind. While any exists, SIGINT, SIGTERM and SIGHUP to this
// process kill the running workers (run_child_process's children), remove every scratch
// directory still there, and then end the process as the signal would have. (A SIGKILL cannot
// be caught: the next count sweeps the directories of processes that are gone.)
#pragma once

#include <filesystem>
#include <string>

namespace watergen {

class ScratchDirectory {
  public:
    // <root>/<prefix><pid>-<n>, n counting this process's directories; error() says why not.
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
};

// Removes <root>/<prefix><pid>-* for every pid that is no longer a running process (left by a
// process that was killed outright); returns how many went.
size_t sweep_stale_scratch(const std::filesystem::path& root, const std::string& prefix);

} // namespace watergen
