// normals: see apply_normals in watergen/surface.h and core/nodes/normals.cpp.
#pragma once

#include "watergen/dsl.h"

namespace watergen {

} // namespace watergen
