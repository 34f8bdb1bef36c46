// refraction: see apply_refraction in watergen/surface.h and core/nodes/refraction.cpp.
#pragma once

#include "watergen/dsl.h"

namespace watergen {

} // namespace watergen
