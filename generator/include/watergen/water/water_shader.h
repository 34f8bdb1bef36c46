// Composes the fullscreen water pass (the post-process formulation of seed 000) from the
// feature node chosen on each axis.
#pragma once

#include "watergen/ir/ir.h"
#include "watergen/water/variant.h"

namespace watergen {

// Textures of the water pass. The scene is rendered first; the water pass reads it back.
TextureInput scene_color_texture();    // lit colour of what lies under / behind the water, rgb
TextureInput scene_position_texture(); // world position of that surface, xyz (m)

struct Preset;

struct WaterShader {
    Variant variant;
    std::string preset; // name of the preset applied to the parameter defaults, "" for none
    Graph fragment;     // inputs: varying v_uv; output "color" (vec4, linear HDR)
};

// Builds the fragment graph; type errors end up in fragment.diagnostics().
// A preset replaces the defaults of the parameters it names.
WaterShader build_water_shader(const Variant& variant, const Preset* preset = nullptr);

} // namespace watergen
