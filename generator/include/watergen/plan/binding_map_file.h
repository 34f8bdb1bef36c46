// A binding map (ir/binding_map.h) as a JSON file, read and written:
//
//   {
//     "watergen_bindings": 1,
//     "base": "frequency_sets",            // optional: start from a profile
//     "resources": {
//       "WaterParams": {"set": 2, "binding": 0, "hlsl_register": 0, "hlsl_space": 2,
//                       "msl": 0, "gl": 0},
//       "scene_color": {"set": 0, "binding": 7}
//     }
//   }
//
// An entry for a resource the base already places changes the keys it gives; an entry for a
// new resource needs "set" and "binding", and its other places default to the binding (HLSL
// register, Metal index, GL unit) and the set (HLSL space). "kind" ("uniform_block", "sampler",
// "texture") defaults from the name (binding_map.h). Indices are at most kMaxBindingIndex, sets
// at most kMaxSet (Vulkan guarantees maxBoundDescriptorSets >= 4).
//
// The parameter block as a push constant: {"WaterParams": {"kind": "push_constant"}} (only "msl"
// and "gl" beside the kind: a push constant has no set, binding or register) and, at the top,
// "push_constant_bytes" (the range's size: a multiple of 16 up to kMaxPushConstantBytes; default
// kGuaranteedPushConstantBytes, the 128 every Vulkan device pushes).
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "watergen/ir/core/diagnostic.h"
#include "watergen/ir/emit/binding_map.h"
#include "watergen/plan/json_source.h"

namespace watergen {

constexpr uint32_t kMaxBindingIndex = 4095;
constexpr uint32_t kMaxSet = 3;

// The map in `source`; nullopt and a diagnostic at the offending key (file:line:column, the
// JSON pointer, what was expected); a clash names both resources and both lines.
std::optional<BindingMap> read_binding_map(const JsonSource& source, Diagnostics& diagnostics);
// A profile's name (water/binding_profiles.h), else the path of a map file.
std::optional<BindingMap> load_binding_map(const std::string& profile_or_path,
                                           Diagnostics& diagnostics);
// The map as a file read_binding_map reads back (no base: every slot spelled out).
nlohmann::ordered_json binding_map_json(const BindingMap& map);

} // namespace watergen
