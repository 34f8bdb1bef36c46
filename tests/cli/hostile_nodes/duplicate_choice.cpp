// A project that registers a Fresnel choice watergen already has: its generator stops at start
// with this file and line (exit 2) before any command runs.
#include "watergen/water/axis_registry.h"
#include "watergen/water/surface.h"

WATERGEN_REGISTER_NODES(register_duplicate) {
    watergen::register_choice("fresnel", {.name = "schlick",
                                          .description = "a second schlick",
                                          .compose = [](watergen::Surface&) {}});
}
