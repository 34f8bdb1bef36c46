// Nodes with mistakes a project can make, each a choice on watergen's fresnel axis: the build
// of a variant that offers one fails with this file and the registering line, exit 2, and
// writes nothing.
//   fresnel=type_error  adds a vec3 to a vec2
//   fresnel=ior_clash   declares watergen's ior_water with another default
#include "watergen/water/axis_registry.h"
#include "watergen/water/surface.h"

namespace {

using namespace watergen;

void add_vec3_to_vec2(Surface& s) {
    s.fresnel = (s.normal + s.uv).x();
}

void declare_another_ior_water(Surface& s) {
    s.fresnel =
        saturate(uniform(s.g, {"ior_water", Type::Float, {1.5}, 1.0, 3.0, "", "001", ""}) - 1.0);
}

} // namespace

WATERGEN_REGISTER_NODES(register_broken_nodes) {
    watergen::register_choice("fresnel", {.name = "type_error",
                                          .description = "adds a vec3 to a vec2",
                                          .compose = &add_vec3_to_vec2});
    watergen::register_choice("fresnel", {.name = "ior_clash",
                                          .description = "ior_water with another default",
                                          .compose = &declare_another_ior_water});
}
