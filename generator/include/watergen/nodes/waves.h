// waves: see apply_waves in watergen/surface.h and core/nodes/waves.cpp.
#pragma once

#include "watergen/dsl.h"

namespace watergen {

} // namespace watergen
