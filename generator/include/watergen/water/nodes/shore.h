// Shore: how the water meets the land.
#pragma once

#include "watergen/ir/core/dsl.h"

namespace watergen {

// 000: colour = mix(refracted, colour, saturate(depth * shore_hardness)).
Expr shore_soft(Graph& g, Expr color, Expr refracted, Expr depth);

} // namespace watergen
