// Ready binding maps (ir/binding_map.h) for the resources of watergen's own nodes, after the
// descriptor conventions engines use:
// - "watergen" (the default): set 0; the block at 0, the sampler at 1, the textures from 2.
// - "frequency_sets": sets by update frequency, as Filament lays them out (set 0 per view,
//   1 per renderable, 2 per material): what the renderer makes each view (scene colour and
//   position, sky, planar reflection, caustics map) in set 0; the parameter block, the sampler
//   and the material's own textures in set 2; set 1 is left to the engine's per-object data.
// - "register_spaces": D3D12-style register spaces, each Vulkan set the space of the same
//   number with bindings shifted per register class (b + 0, t + 16, s + 32, as DXC's
//   -fvk-*-shift options do): the block b0 and the sampler s0 in space0, the per-view textures
//   t0.. in space1, the material's textures t0.. in space2.
// Every slot keeps its place in every variant, so one layout serves a whole material.
#pragma once

#include <string>
#include <vector>

#include "watergen/ir/emit/binding_map.h"

namespace watergen {

// The profile of that name; nullptr for another.
const BindingMap* binding_profile(const std::string& name);
const std::vector<std::string>& binding_profile_names();
std::string binding_profile_list();      // "watergen, frequency_sets, register_spaces"
const BindingMap& default_binding_map(); // "watergen"

} // namespace watergen
