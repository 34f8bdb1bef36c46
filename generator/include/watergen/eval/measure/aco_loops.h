// The loops of an ACO disassembly, and a per-pixel instruction estimate from them.
//
// ACO's "Instructions" statistic is static: a loop body counts once however often it runs. The
// disassembly shows each loop as a block label that a later branch jumps back to; the
// instructions from the label to that branch are the body. The IR knows each loop's trip count
// (LoopBody::trip_count), so an estimate of the instructions one pixel executes weights every
// body by its trip count, nested ones by the product.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace watergen {

struct AsmLoop {
    uint32_t first = 0, last = 0; // instruction indices: the header's first, the back branch
    uint32_t instructions = 0;    // last - first + 1: the body, nested loops included
    uint32_t depth = 0;           // 0 outermost
};

struct AsmListing {
    uint32_t instructions = 0;  // instruction lines (labels, comments and the end marker not)
    std::vector<AsmLoop> loops; // by header, in program order (an outer loop before its inner)
};

// Reads ACO's disassembly: "BB<n>:" labels, one instruction per line ("s_cbranch_scc1 BB3"
// names its target), "s_code_end" padding not counted. nullopt and *error for a branch to a
// label the listing does not define or loops that overlap without nesting.
std::optional<AsmListing> read_aco_listing(const std::string& disassembly, std::string* error);

// The instructions a pixel executes if loop i runs trip_counts[i] times (loops in the order
// read_aco_listing gives them; a nested loop's count is per iteration of its outer loop):
// every instruction weighted by the product of the trip counts of the loops around it.
// nullopt when the counts do not match the loops one to one.
std::optional<double> weighted_instructions(const AsmListing& listing,
                                            const std::vector<double>& trip_counts);

} // namespace watergen
