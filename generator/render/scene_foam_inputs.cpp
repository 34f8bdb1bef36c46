#include "watergen/synthetic_scene.h"

namespace watergen {

void add_foam_inputs(SyntheticScene&) {}

} // namespace watergen
