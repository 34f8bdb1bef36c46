// Stages compiled once per build. Every variant of a build has the same full-screen vertex
// shader, and variants of different scenes can fold to the same fragment; their sources differ
// only in the stamp comment that names the variant, which no compiler output depends on. The
// memo keys a stage by its content (language, stage, options, source with the stamp blank),
// compiles the first request for it and hands its outputs to the others.
#pragma once

#include <compare>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>

#include "watergen/toolchain/toolchain.h"

namespace watergen {

// The content key of a stage: XXH3-128 of `request` with the stamp of `variant_key` blanked in
// its source (stamp_text(""), emitter.h) and of how far the chain runs. Equal keys, equal
// outputs. 128 bits in 16 bytes: over the millions of stages of a large build a 64-bit key
// could collide, and a collision would hand one stage another's outputs.
struct StageKey {
    uint64_t high = 0, low = 0;
    bool empty() const { return high == 0 && low == 0; }
    auto operator<=>(const StageKey&) const = default;
};
StageKey stage_key(const CompileRequest& request, CrossCompile cross,
                   const std::string& variant_key);
// `source` with the stamp line of `variant_key` replaced by the blank stamp; lines keep their
// numbers, so diagnostics point where they did.
std::string blank_stamp(const std::string& source, const std::string& variant_key);

struct StageCounts {
    size_t compiled = 0; // toolchain runs
    size_t reused = 0;   // stages handed outputs compiled for another variant
};

class StageMemo {
  public:
    // Outputs held at once, at most (a fragment's are ~100 KB): past it a shared stage is
    // compiled again rather than kept.
    static constexpr size_t kDefaultMaxBytes = size_t{64} << 20;
    explicit StageMemo(size_t max_bytes = kDefaultMaxBytes) : max_bytes_(max_bytes) {}

    // Planning, before any run(): the stages the build's variants will compile, one key per
    // use. Only a stage expected more than once is kept, and only until its last expected use (a
    // variant that finds its files in the cache never comes, so its share stays until the end:
    // within max_bytes); only those get an entry (a build's fragments are mostly its own), so a
    // plan of millions of stages holds 16 bytes each while it is counted, not an entry each.
    void expect(std::vector<StageKey> keys);

    // The toolchain outputs of `request` (its stamp blanked, see stage_key) for a variant keyed
    // `variant_key`. Thread-safe; a caller that asks while another compiles the same stage waits
    // for it instead of compiling it again.
    ToolchainOutputs run(const CompileRequest& request, CrossCompile cross,
                         const std::string& variant_key);

    StageCounts counts() const;
    // Stages planned or held now (what the memo's memory grows with).
    size_t entries() const;

  private:
    struct Entry {
        size_t expected = 0; // uses left, this one's included
        enum class State { Waiting, Compiling, Done } state = State::Waiting;
        ToolchainOutputs outputs;
        size_t bytes = 0;
    };
    ToolchainOutputs take(std::map<StageKey, Entry>::iterator it);

    size_t max_bytes_;
    size_t held_bytes_ = 0;
    mutable std::mutex lock_;
    std::condition_variable done_;
    std::map<StageKey, Entry> entries_;
    StageCounts counts_;
};

} // namespace watergen
