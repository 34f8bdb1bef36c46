// specular: see apply_specular in watergen/surface.h and core/nodes/specular.cpp.
#pragma once

#include "watergen/dsl.h"

namespace watergen {

} // namespace watergen
