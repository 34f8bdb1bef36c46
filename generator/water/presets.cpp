#include "watergen/water/presets.h"

#include "watergen/ir/core/text.h"

namespace watergen {

const std::vector<Preset>& presets() {
    // Values cite their seed where they come from one; the rest are chosen to look like the
    // named water under the synthetic scene and stay inside each parameter's range.
    static const std::vector<Preset> list = {
        {"tropical_ocean",
         "clear warm sea over sand (003's tropical set)",
         {
             {"absorb_coefficients", {0.46, 0.09, 0.06}}, // 003
             {"scatter_coefficient", {0.11}},             // 003
             {"scatter_color", {0.05, 0.05, 0.10}},       // 003
             {"sky_color", {0.55, 0.7, 0.9}},
             {"sun_direction", {-0.35, -0.75, 0.55}},
             {"sun_color", {1.0, 0.95, 0.85}},
         }},
        {"muddy_river",
         "turbid brown water: strong scattering, little light reaches the bed",
         {
             {"absorb_coefficients", {0.9, 1.1, 1.6}},
             {"scatter_coefficient", {1.2}},
             {"scatter_color", {0.22, 0.17, 0.08}},
             {"sky_color", {0.6, 0.65, 0.7}},
             {"sun_direction", {-0.2, -0.6, 0.77}},
             {"sun_color", {0.9, 0.85, 0.75}},
         }},
        {"mountain_lake",
         "cold clear lake, deep green-blue",
         {
             {"absorb_coefficients", {0.35, 0.12, 0.1}},
             {"scatter_coefficient", {0.05}},
             {"scatter_color", {0.01, 0.05, 0.06}},
             {"sky_color", {0.45, 0.6, 0.85}},
             {"sun_direction", {0.3, -0.85, 0.43}},
             {"sun_color", {1.0, 1.0, 0.95}},
         }},
        {"harbour_at_night",
         "sun below the horizon: no sun highlight, dark sky, murky water",
         {
             {"absorb_coefficients", {0.6, 0.4, 0.35}},
             {"scatter_coefficient", {0.4}},
             {"scatter_color", {0.01, 0.015, 0.02}},
             {"sky_color", {0.02, 0.03, 0.06}},
             {"sun_direction",
              {0.2, 0.3, 0.93}}, // travelling upwards: the sun is below the horizon
             {"sun_color", {0.05, 0.05, 0.08}},
             {"incident_light", {0.08, 0.08, 0.12}},
         }},
    };
    return list;
}

const Preset* find_preset(const std::string& name) {
    for (const auto& p : presets())
        if (p.name == name) return &p;
    return nullptr;
}

std::string preset_names() {
    return join(presets(), [](const Preset& p) { return p.name; });
}

std::vector<std::string> apply_preset(Graph& g, const Preset& preset) {
    std::vector<std::string> mismatched;
    for (const auto& [name, values] : preset.values)
        if (!g.set_parameter_default(name, values) && g.find_parameter(name))
            mismatched.push_back(name);
    return mismatched;
}

} // namespace watergen
