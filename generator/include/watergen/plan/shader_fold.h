// The scene's fixed values and ranges, folded into every graph of a water shader: the vertex
// and tessellation stages of a mesh geometry as its fragment, so one uniform block (the one a
// build's stages share) holds the same parameters with the same ranges in every stage, and no
// stage reads a value the scene fixed.
#pragma once

#include "watergen/ir/fold/ir_fold.h"
#include "watergen/water/water_shader.h"

namespace watergen {

// Folds each graph of `shader` under `facts`, in place. The report is the fragment's, with the
// parameters and textures the other stages no longer read added to its removed ones (a
// parameter counts as removed when no stage reads it).
FoldReport fold_water_shader(WaterShader& shader, const FoldFacts& facts);

} // namespace watergen
