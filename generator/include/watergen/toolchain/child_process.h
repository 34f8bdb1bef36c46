// Runs a program as a child process (fork and execve, no shell) and waits for it. The child
// dies with this process (PR_SET_PDEATHSIG SIGKILL), however this process ends.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace watergen {

// What:   runs argv[0] (from PATH, or a path) with stdin from /dev/null and stdout / stderr
//         sent to <dir>/<name>.stdout and .stderr, <name> the file name of argv[0].
//         The child gets this process's environment with `env` over it: "NAME=value" sets
//         NAME, a bare "NAME" removes it; this process's own environment does not change.
// Output: "" on exit status 0; else "<argv[0]>: exit status N" (or "killed by signal N") and
//         the start of its stderr (its stdout when stderr is empty).
std::string run_child_process(const std::vector<std::string>& argv,
                              const std::filesystem::path& dir,
                              const std::vector<std::string>& env = {});

// For a signal handler (async-signal-safe): SIGKILL to every child run_child_process is waiting
// for now, then wait until each has exited (without reaping it: its caller does).
void kill_child_processes();
void wait_for_killed_children();

} // namespace watergen
