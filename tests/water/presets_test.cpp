#include <catch2/catch.hpp>

#include <map>

#include "watergen/plan/covering_array.h"
#include "watergen/water/presets.h"
#include "watergen/water/water_shader.h"

using namespace watergen;

// Every preset value names a parameter some node declares, with its size, inside its range:
// a renamed parameter or a typo would otherwise silently do nothing.
TEST_CASE("presets_name_existing_parameters_within_their_ranges", "[presets]") {
    std::map<std::string, Parameter> declared;
    for (const Variant& v : pairwise_covering_variants()) {
        const WaterShader shader = build_water_shader(v);
        for (const auto& p : shader.fragment.parameters())
            declared.emplace(p.name, p);
    }
    for (const char* name : {"tropical_ocean", "muddy_river", "mountain_lake", "harbour_at_night"})
        REQUIRE(find_preset(name) != nullptr);
    for (const auto& preset : presets())
        for (const auto& [name, values] : preset.values) {
            INFO(preset.name << ": " << name);
            REQUIRE(declared.count(name) == 1);
            const Parameter& p = declared.at(name);
            REQUIRE(values.size() == p.default_value.size());
            for (double v : values) {
                CHECK(v >= p.min);
                CHECK(v <= p.max);
            }
        }
}

TEST_CASE("a_preset_replaces_parameter_defaults", "[presets]") {
    const WaterShader shader = build_water_shader(default_variant(), find_preset("muddy_river"));
    const Parameter* b = shader.fragment.find_parameter("scatter_coefficient");
    REQUIRE(b != nullptr);
    CHECK(b->default_value == std::vector<double>{1.2});
    CHECK(shader.preset == "muddy_river");
}

TEST_CASE("harbour_at_night_puts_the_sun_below_the_horizon", "[presets]") {
    const auto& sun = find_preset("harbour_at_night")->values.at("sun_direction");
    CHECK(sun[1] > 0.0); // light travelling upwards comes from below the horizon
}
