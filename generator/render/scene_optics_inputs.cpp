#include "watergen/synthetic_scene.h"

namespace watergen {

void add_optics_inputs(SyntheticScene&) {}

} // namespace watergen
