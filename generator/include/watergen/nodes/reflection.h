// Reflection: what the surface mirrors.
#pragma once

#include "watergen/dsl.h"

namespace watergen {

Parameter sky_color(); // constant sky (choice "none"), and the fallback of the others

} // namespace watergen
