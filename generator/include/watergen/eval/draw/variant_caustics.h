// What `watergen render` adds for a variant with caustics (texture, area_ratio, photon_splat):
// for a pass choice, the pass drawn for the scene (scene_caustics_pass.h), whose texture the
// scene then carries for the water pass and the CPU evaluator; the texture the water samples as
// caustics.png, the lit bottom (caustics_bottom.h) as bottom_lit.png, and render.json's
// "caustics" block. For caustics=none nothing runs and nothing is added.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "watergen/eval/draw/scene_caustics_pass.h"
#include "watergen/water/variant.h"

namespace watergen {

struct RenderCaustics {
    std::string choice;                    // the variant's caustics choice
    std::optional<SceneCausticsPass> pass; // area_ratio, photon_splat
    std::vector<double> texture;           // what the water samples: the pass's map, or the tile
    uint32_t texels = 0;
    ImageRGBA32F lit_bottom;
    std::string error;
    bool ok() const { return error.empty(); }
};

// Whether `variant` has caustics (anything but caustics=none).
bool has_caustics(const Variant& variant);

// Before the variant's render: draws its pass (if any, `timed_draws` timed draws) for `scene`,
// puts the texture into `scene`, and evaluates the lit bottom over the result. The pass is the
// one a build of a material of `preset` alone ships (build_caustics_pass_files).
RenderCaustics prepare_render_caustics(VulkanRunner& runner, const Variant& variant,
                                       const VariantBuild& water, SyntheticScene& scene,
                                       uint32_t timed_draws, const Preset* preset = nullptr);

// render.json's "caustics" block: the choice, the texture and its tone map, and for a pass its
// method, wave model, depth, window, draw times and error against the CPU reference.
nlohmann::ordered_json render_caustics_json(const RenderCaustics& c);

// caustics.png (kCausticsToneMap) and bottom_lit.png (at `exposure`, like the renders), as
// bytes by name; nullopt with the reason in *error if an image cannot be encoded.
std::optional<std::map<std::string, std::string>>
render_caustics_files(const RenderCaustics& c, float exposure, std::string* error);

} // namespace watergen
