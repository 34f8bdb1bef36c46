// foam: see apply_foam in watergen/surface.h and core/nodes/foam.cpp.
#pragma once

#include "watergen/dsl.h"

namespace watergen {

} // namespace watergen
