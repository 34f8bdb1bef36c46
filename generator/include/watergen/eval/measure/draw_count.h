// A draw's cost that does not depend on machine load: the instructions lavapipe executes for
// it, counted exactly by valgrind's callgrind tool. The runner brackets two spans
// (RenderJob::counted_draw_label): pipeline creation through the first draw ("<label> first",
// lavapipe's JIT compile of the shaders and one draw), and one steady draw ("<label>"), with
// instrumentation off for everything else (setup, the timed draws, the readback).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace watergen {

struct DrawCount {
    std::string label;         // RenderJob::counted_draw_label, with " first" for the JIT span
    uint64_t instructions = 0; // guest instructions executed during the draw (callgrind Ir)
};

struct DrawCountRun {
    std::vector<DrawCount> counts; // in the order the worker drew them
    std::string error;             // "" when the worker ran and every dump was read
    bool ok() const { return error.empty(); }
};

// What:   runs `worker_argv` under `valgrind --tool=callgrind --instr-atstart=no` with its
//         dumps in a directory of its own under `scratch` (created, removed afterwards; the
//         process id and a counter keep concurrent calls apart), lavapipe drawing
//         on the calling thread (LP_NUM_THREADS=0, so thread scheduling cannot change the
//         count) and Mesa's shader cache off; then reads one count per bracketed draw.
// Cost:   the worker at valgrind speed: about 5 s per pipeline JIT-compiled under it, plus
//         the counted draws at callgrind speed (~50x native).
DrawCountRun count_draws_under_valgrind(const std::vector<std::string>& worker_argv,
                                        const std::filesystem::path& scratch);

// The steady draws' counts of a run by label (the " first" spans left out); nullopt and
// *error when the run failed.
std::optional<std::map<std::string, uint64_t>> steady_draw_counts(const DrawCountRun& run,
                                                                  std::string* error);

// The worker argv that counts the draws of the given variant keys.
using KeyedWorker = std::function<std::vector<std::string>(const std::vector<std::string>& keys)>;

// Counts `keys` (labels = keys, a repeated key "<key>#2") in up to `workers` valgrind runs at
// once, every occurrence of a key in the same run, and merges their steady draw counts.
// Instruction counts do not depend on load, so the runs may share the cores.
std::optional<std::map<std::string, uint64_t>>
count_keys_in_parallel(const std::vector<std::string>& keys, const KeyedWorker& worker_argv,
                       const std::filesystem::path& scratch, unsigned workers, std::string* error);

// One callgrind dump ("desc: Trigger: Client Request: <label>" ... "totals: <Ir>"); nullopt
// for a dump that no client request triggered or that has no totals line.
std::optional<DrawCount> parse_callgrind_dump(const std::string& text);

} // namespace watergen
