// Composes the fullscreen water pass (the post-process formulation of seed 000) from the
// feature node chosen on each axis, or, for a shader that serves several variants, from the
// choices offered on each axis (a switch per axis with more than one).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "watergen/ir/core/ir.h"
#include "watergen/water/mesh_shader.h"
#include "watergen/water/variant.h"

namespace watergen {

// Textures of the water pass. The scene is rendered first; the water pass reads it back.
TextureInput scene_color_texture();    // lit colour of what lies under / behind the water, rgb
TextureInput scene_position_texture(); // that surface less the eye, xyz (m): camera-relative

struct Preset;

// How variants become shaders (watergen build --mode). Permutations: one shader per variant.
// Specialized and Branching: one shader for many variants, in which each axis offered with
// several choices is a switch (dsl.h, choose()) on its selector parameter, axis_<name>, whose
// value is the index of the variant's choice among the offered ones: a specialization constant
// (Specialized: set at pipeline creation, or frozen offline) or a uniform-block member
// (Branching: read at run time). The precision axis changes the types of all the shading, so it
// stays a permutation: one shader per precision.
enum class BuildMode { Permutations, Specialized, Branching };
const char* to_string(BuildMode m);
std::optional<BuildMode> parse_build_mode(const std::string& name);
std::string build_mode_names(); // "permutations, specialized, branching"

// The selector parameter of an axis: "axis_fresnel".
std::string selector_parameter(const std::string& axis);
// Whether an axis is always a permutation (one shader per choice): its AxisInfo says so.
bool permutation_only(const std::string& axis);

// The choices one shader composes on each axis: one per axis for a variant; several on the
// switched axes of a shader that serves many.
struct ShaderChoices {
    BuildMode mode = BuildMode::Permutations;
    std::vector<std::vector<std::string>> choices; // per axis, axes() order; registry order within

    static ShaderChoices of(const Variant& v);
    // The choices offered on `axis` (empty for an unknown axis).
    const std::vector<std::string>& offered(const std::string& axis) const;
    // "fresnel=schlick|exact,extinction=absorb_scatter,..."
    std::string key() const;
    // "fresnel-schlick+exact_extinction-absorb_scatter_...": safe as a file name
    std::string file_stem() const;
    bool covers(const Variant& v) const;
    // Axes with more than one choice, in axes() order.
    std::vector<std::string> switched_axes() const;
    // Selector parameter -> the value that makes the shader draw `v` (which it must cover).
    std::map<std::string, double> selector_values(const Variant& v) const;
    // The variant the selectors' defaults (0) draw: each axis' first choice.
    Variant first_variant() const;
};

// The shaders `mode` makes of `variants`: one per variant (Permutations), or one per choice of
// the permutation-only axes, offering on every other axis the choices its variants use.
std::vector<ShaderChoices> shaders_for(const std::vector<Variant>& variants, BuildMode mode);

struct WaterShader {
    Variant variant;    // the variant; for a switched shader, the one its selectors' defaults draw
    std::string preset; // name of the preset applied to the parameter defaults, "" for none
    // Inputs: varying v_uv (the screen pass) or mesh_fragment_inputs(); output "color" (vec4,
    // linear HDR).
    Graph fragment;
    std::optional<ShaderChoices> switched = std::nullopt; // a shader serving several variants
    // The stages before the fragment of a mesh geometry (geometry=mesh or tessellated); none
    // for the screen pass, whose vertex stage is the fullscreen triangle.
    std::optional<MeshStages> mesh = std::nullopt;

    // The variant's key, or the switched shader's (ShaderChoices::key).
    std::string key() const { return switched ? switched->key() : variant.key(); }
};

// How the screen pass finds the surface: as the waves choice ships, or its search run to
// convergence (compose_converged_waves), the reference a mesh geometry is measured against.
enum class SurfaceSearch { AsChosen, Converged };

// Builds the fragment graph; type errors end up in fragment.diagnostics().
// A preset replaces the defaults of the parameters it names.
WaterShader build_water_shader(const Variant& variant, const Preset* preset = nullptr,
                               SurfaceSearch search = SurfaceSearch::AsChosen);
// The same for several choices per axis (a permutation when every axis has one).
WaterShader build_water_shader(const ShaderChoices& choices, const Preset* preset = nullptr,
                               SurfaceSearch search = SurfaceSearch::AsChosen);

} // namespace watergen
