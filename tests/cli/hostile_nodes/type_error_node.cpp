// A project's Fresnel choice that adds a vec3 to a vec2: its generator stops at start with this
// file and the registering line, the node named, exit 2, before any command writes anything.
#include "watergen/water/axis_registry.h"
#include "watergen/water/surface.h"

namespace {

using namespace watergen;

void add_vec3_to_vec2(Surface& s) {
    s.fresnel = (s.normal + s.uv).x();
}

} // namespace

WATERGEN_REGISTER_NODES(register_type_error) {
    watergen::register_choice("fresnel", {.name = "type_error",
                                          .description = "adds a vec3 to a vec2",
                                          .compose = &add_vec3_to_vec2});
}
