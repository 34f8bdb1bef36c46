// A project's Fresnel choice that declares watergen's ior_water with another default: its
// generator stops at start naming both definitions (this file's and watergen's), exit 2, even
// for a command whose variant holds only this one.
#include "watergen/water/axis_registry.h"
#include "watergen/water/surface.h"

namespace {

using namespace watergen;

void declare_another_ior_water(Surface& s) {
    // A declaration of its own: GCC and clang both date it at its closing brace (WG_IOR_CLASH).
    const Parameter ior{.name = "ior_water",
                        .type = Type::Float,
                        .default_value = {1.5},
                        .min = 1.0,
                        .max = 3.0,
                        .seed = "001"};
    s.fresnel = saturate(uniform(s.g, ior) - 1.0);
}

} // namespace

WATERGEN_REGISTER_NODES(register_ior_clash) {
    watergen::register_choice("fresnel", {.name = "ior_clash",
                                          .description = "ior_water with another default",
                                          .compose = &declare_another_ior_water});
}
