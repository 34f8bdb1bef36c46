#include "watergen/synthetic_scene.h"

namespace watergen {

void add_wave_inputs(SyntheticScene&) {}

} // namespace watergen
