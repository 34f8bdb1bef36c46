// A small set of variants in which every feasible pair of choices on two different axes
// appears at least once: what CI compiles and renders instead of the whole space.
#pragma once

#include <vector>

#include "watergen/water/variant.h"

namespace watergen {

// Deterministic greedy construction (each new variant starts from the first uncovered pair and
// takes, axis by axis, the choice that covers most uncovered pairs). Every variant satisfies
// builtin_rules(); pairs that no valid variant can hold are left out.
std::vector<Variant> pairwise_covering_variants();

} // namespace watergen
