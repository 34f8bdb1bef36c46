// Named parameter sets: the same shader variants tuned for a kind of water. A preset only
// overrides parameter values; which nodes a variant uses stays the variant's choice.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "watergen/ir/core/ir.h"

namespace watergen {

struct Preset {
    std::string name;
    std::string description;
    std::map<std::string, std::vector<double>> values; // parameter name -> components
};

const std::vector<Preset>& presets();
const Preset* find_preset(const std::string& name);
std::string preset_names(); // "a, b, c"

// Replaces the defaults of the graph's parameters named by the preset (others are left as
// they are; a preset may name parameters of nodes this variant does not use). Returns the
// names whose component count did not match, which callers report as errors.
std::vector<std::string> apply_preset(Graph& g, const Preset& preset);

} // namespace watergen
