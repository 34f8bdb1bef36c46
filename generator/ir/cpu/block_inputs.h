// What a compiled program's leaves and texture samples read from the evaluation's inputs, and
// the checks that fail the evaluation when an input is missing or malformed. Private to ir/.
#pragma once

#include <vector>

#include "block_program.h"

namespace watergen {

// Instr::data for node n of graph g (a loop body reads its enclosing graph `top`'s parameters):
// a constant's or parameter's components, an array parameter's elements, a varying's values, a
// TextureView; nullptr for other nodes. Appends to `checks` what can fail, in node order.
// A parameter with a host rule reads its value from `host` (shader_values.h).
const void* input_data(const Graph& top, const Graph& g, const Node& n, uint32_t comps,
                       const EvalInputs& in, const ParameterValues& host,
                       std::vector<Check>& checks);

} // namespace watergen
