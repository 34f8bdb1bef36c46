#include "watergen/eval/measure/draw_count.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <fstream>
#include <future>
#include <sstream>

#include <unistd.h>

#include "watergen/eval/measure/scratch_directory.h"
#include "watergen/toolchain/child_process.h"

namespace watergen {

namespace fs = std::filesystem;

std::optional<DrawCount> parse_callgrind_dump(const std::string& text) {
    static const std::string kTrigger = "desc: Trigger: Client Request: ";
    static const std::string kTotals = "totals: ";
    DrawCount count;
    bool labelled = false, counted = false;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (line.rfind(kTrigger, 0) == 0) {
            count.label = line.substr(kTrigger.size());
            labelled = true;
        } else if (line.rfind(kTotals, 0) == 0) {
            // "totals:" sums the dump's cost lines, over every thread. (Its "summary:" line
            // misses the other threads' work after instrumentation was switched off and on.)
            const std::string value = line.substr(kTotals.size());
            char* end = nullptr;
            count.instructions = std::strtoull(value.c_str(), &end, 10);
            counted = end != value.c_str();
        }
    }
    if (!labelled || !counted) return std::nullopt;
    return count;
}

DrawCountRun count_draws_under_valgrind(const std::vector<std::string>& worker_argv,
                                        const fs::path& scratch_root) {
    DrawCountRun run;
    // A directory of this call's own: two counts at once (two watergen processes, or ctest -j)
    // must not read or clear each other's dumps, and the caller's directory is never cleared.
    // Removed on every way out, a kill of this process included (scratch_directory.h).
    const ScratchDirectory dir(scratch_root, "watergen-count-");
    if (!dir.error().empty()) {
        run.error = dir.error();
        return run;
    }
    const fs::path& scratch = dir.path();
    const fs::path out = scratch / "callgrind.out";
    // --vgdb=no: no gdbserver FIFOs in $TMPDIR, which a killed worker would leave behind.
    std::vector<std::string> argv = {"valgrind", "--tool=callgrind", "--vgdb=no",
                                     "--instr-atstart=no", "--callgrind-out-file=" + out.string()};
    argv.insert(argv.end(), worker_argv.begin(), worker_argv.end());
    run.error =
        run_child_process(argv, scratch, {"LP_NUM_THREADS=0", "MESA_SHADER_CACHE_DISABLE=true"});
    if (!run.ok()) return run;
    // callgrind.out.1, .2, ...: one per client-request dump, in the order they were taken.
    for (int k = 1;; ++k) {
        std::ifstream in(out.string() + "." + std::to_string(k));
        if (!in) break;
        std::ostringstream text;
        text << in.rdbuf();
        if (auto c = parse_callgrind_dump(text.str())) run.counts.push_back(*c);
    }
    if (run.counts.empty()) run.error = "the worker bracketed no draw (no callgrind dump)";
    return run;
}

std::optional<std::map<std::string, uint64_t>> steady_draw_counts(const DrawCountRun& run,
                                                                  std::string* error) {
    if (!run.ok()) {
        *error = run.error;
        return std::nullopt;
    }
    static const std::string kFirst = " first";
    std::map<std::string, uint64_t> out;
    for (const DrawCount& c : run.counts)
        if (c.label.size() < kFirst.size() ||
            c.label.compare(c.label.size() - kFirst.size(), kFirst.size(), kFirst) != 0)
            out[c.label] = c.instructions;
    return out;
}

std::optional<std::map<std::string, uint64_t>>
count_keys_in_parallel(const std::vector<std::string>& keys, const KeyedWorker& worker_argv,
                       const std::filesystem::path& scratch, unsigned workers, std::string* error) {
    // Distinct keys dealt round-robin; every occurrence goes where its key went.
    std::map<std::string, size_t> run_of;
    std::vector<std::vector<std::string>> parts;
    for (const std::string& key : keys) {
        auto [it, added] = run_of.emplace(key, run_of.size() % std::max(workers, 1u));
        if (it->second >= parts.size()) parts.resize(it->second + 1);
        parts[it->second].push_back(key);
    }
    std::vector<std::future<DrawCountRun>> runs;
    for (const auto& part : parts)
        runs.push_back(std::async(std::launch::async, [&, part] {
            return count_draws_under_valgrind(worker_argv(part), scratch);
        }));
    std::map<std::string, uint64_t> out;
    for (auto& run : runs) {
        const auto counts = steady_draw_counts(run.get(), error);
        if (!counts) return std::nullopt;
        out.insert(counts->begin(), counts->end());
    }
    return out;
}

} // namespace watergen
