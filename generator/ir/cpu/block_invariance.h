// Which values of a loop body the compiled program (block_program.h) holds lane-invariant: one
// value for all the block's lanes. Private to ir/.
#pragma once

#include <vector>

#include "watergen/ir/core/ir.h"

namespace watergen {

// Per carried value of Loop node `loop`, whether it is the same on every lane, given which of
// the node's arguments are (`args`, one per argument). It is when its initial value is and its
// next value is computed from lane-invariant values only (a fixed point: carried values that
// are assumed to be are dropped until none is dropped). A loop with an exit has none: lanes
// leave it after different iterations.
//
// The rules are block_program.cpp's, or more cautious (a switch's results vary): a value found
// lane-invariant here is lane-invariant when compiled.
std::vector<char> invariant_carried(const Node& loop, const std::vector<char>& args);

} // namespace watergen
