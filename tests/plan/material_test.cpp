#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>

#include "watergen/pipeline/manifest/manifest.h"
#include "watergen/plan/material.h"

using namespace watergen;

namespace {

// The first error of a material description, formatted as the CLI prints it.
std::string error_of(const std::string& text) {
    Diagnostic parse_error;
    const auto src = JsonSource::parse(text, "m.json", &parse_error);
    if (!src) return format_diagnostic(parse_error);
    Diagnostics ds;
    const auto m = parse_material(*src, ds);
    if (m) return "";
    REQUIRE(ds.size() == 1); // one clear error
    return format_diagnostic(ds.front());
}

std::string source_dir() {
    const char* s = std::getenv("WATERGEN_SOURCE_DIR");
    REQUIRE(s != nullptr);
    return s;
}

} // namespace

TEST_CASE("builder_and_file_describe_the_same_material", "[material]") {
    Diagnostics ds;
    const auto file = load_material(source_dir() + "/examples/materials/default.json", ds);
    REQUIRE(file);
    const Material cpp = default_material();
    // The manifest's material section holds everything a build reads from a material.
    CHECK(manifest_json(*file, {}, {}, {}) == manifest_json(cpp, {}, {}, {}));
    CHECK(file->declared.size() == cpp.declared.size());
    CHECK(count_variants(cpp.space) == 144);
}

TEST_CASE("material_space_keeps_documentation_order", "[material]") {
    Diagnostics ds;
    auto a = MaterialBuilder("a").offer("fresnel", {"exact", "none"}).build(ds);
    auto b = MaterialBuilder("a").offer("fresnel", {"none", "exact"}).build(ds);
    REQUIRE(a);
    REQUIRE(b);
    CHECK(a->space.choices == b->space.choices);
    CHECK(a->space.offered("fresnel") == std::vector<std::string>{"none", "exact"});
    // Axes not offered keep their default choice.
    CHECK(a->space.offered("extinction") == std::vector<std::string>{"absorb_scatter"});
}

TEST_CASE("material_errors_name_file_line_path_and_what_was_expected", "[material]") {
    CHECK(error_of("{\n \"name\": \"x\",\n \"axes\": {\"fresnel\": [\"schlick\",]}\n}") ==
          "m.json:3:33: error: invalid JSON: syntax error while parsing value - unexpected ']'; "
          "expected '[', '{', or a literal");
    CHECK(error_of("{\"name\": \"x\",\n \"axes\": {\n  \"colour\": [\"blue\"]}}") ==
          "m.json:3:3: error: /axes/colour: unknown axis 'colour'; expected one of fresnel, "
          "extinction, specular, foam, "
          "reflection, refraction, normals, waves, shore, precision, caustics, scene_input, "
          "geometry");
    CHECK(error_of("{\"name\": \"x\",\n \"axes\": {\"fresnel\": [\"schlick\",\n \"fancy\"]}}") ==
          "m.json:3:2: error: /axes/fresnel/1: unknown fresnel choice 'fancy'; expected one of "
          "none, power, schlick, exact");
    CHECK(error_of("{\"name\": \"x\", \"axes\": {\"fresnel\": [\"exact\", \"exact\"]}}") ==
          "m.json:1:45: error: /axes/fresnel/1: fresnel choice 'exact' is listed twice");
    CHECK(error_of("{\"name\": \"x\",\n \"colour\": 1}") ==
          "m.json:2:2: error: /colour: unknown key 'colour'; expected one of name, description, "
          "preset, axes, rules, "
          "parameters, targets");
    CHECK(error_of("{\"axes\": {}}") == "m.json:1:1: error: /: missing key 'name'");
    CHECK(error_of("{\"name\": 3}") ==
          "m.json:1:2: error: /name: expected a string, got a number (3)");
    CHECK(error_of("{\"name\": \"Bad Name\"}")
              .find("/name: material name 'Bad Name': expected lower-case") != std::string::npos);
}

TEST_CASE("material_type_errors", "[material]") {
    CHECK(error_of("{\"name\": \"x\", \"axes\": {\"fresnel\": \"schlick\"}}") ==
          "m.json:1:24: error: /axes/fresnel: expected an array of choices or \"all\", got a "
          "string (\"schlick\")");
    CHECK(error_of("{\"name\": \"x\", \"axes\": {\"shore\": [\"soft\"]},\n \"parameters\": "
                   "{\"shore_hardness\": {\"value\": \"hard\"}}}") ==
          "m.json:2:36: error: /parameters/shore_hardness/value: expected a number or an array of "
          "numbers, got a string (\"hard\")");
    CHECK(
        error_of(
            "{\"name\": \"x\", \"parameters\": {\"absorb_coefficients\": {\"value\": [1, 2]}}}") ==
        "m.json:1:54: error: /parameters/absorb_coefficients/value: parameter "
        "'absorb_coefficients' is a vec3: expected 3 "
        "numbers, got 2");
    CHECK(error_of("{\"name\": \"x\", \"targets\": [\"glsl\", \"spirv\", \"dxil\"]}") ==
          "m.json:1:44: error: /targets/2: unknown target 'dxil'; expected one of glsl, hlsl, "
          "spirv, glsl330, essl300, msl, reflection");
    CHECK(error_of("{\"name\": \"x\", \"preset\": \"arctic\"}")
              .find("/preset: unknown preset 'arctic'; expected one of tropical_ocean") !=
          std::string::npos);
    CHECK(error_of("{\"name\": \"x\", \"parameters\": {\"shore_hardness\": {\"min\": 1}}}") ==
          "m.json:1:30: error: /parameters/shore_hardness: missing key 'max': a range needs both");
}

TEST_CASE("material_parameters_are_checked_against_the_nodes", "[material]") {
    CHECK(error_of("{\"name\": \"x\", \"parameters\": {\"colour\": {\"value\": 1}}}")
              .find("m.json:1:41: error: /parameters/colour/value: unknown parameter 'colour'; the "
                    "offered nodes read ") == 0);
    CHECK(error_of("{\"name\": \"x\", \"axes\": {\"shore\": [\"soft\"]},\n \"parameters\": "
                   "{\"shore_hardness\": {\"value\": 5000}}}") ==
          "m.json:2:36: error: /parameters/shore_hardness/value: value 5000 of 'shore_hardness' is "
          "out of range; expected a "
          "value in [0, 1000] 1/m");
    CHECK(error_of("{\"name\": \"x\", \"axes\": {\"shore\": [\"soft\"]},\n \"parameters\": "
                   "{\"shore_hardness\": {\"min\": 4, \"max\": 2}}}") ==
          "m.json:2:36: error: /parameters/shore_hardness/min: range of 'shore_hardness': min 4 is "
          "above max 2; expected min <= max");
    // Numbers are spelled in full: two different numbers never read alike.
    CHECK(error_of("{\"name\": \"x\", \"axes\": {\"shore\": [\"soft\"]},\n \"parameters\": "
                   "{\"shore_hardness\": {\"min\": 4.0000001, \"max\": 4}}}") ==
          "m.json:2:36: error: /parameters/shore_hardness/min: range of 'shore_hardness': min "
          "4.0000001 is above max 4; expected min <= max");
    CHECK(error_of("{\"name\": \"x\", \"axes\": {\"shore\": [\"soft\"]},\n \"parameters\": "
                   "{\"shore_hardness\": {\"value\": 1000.25}}}") ==
          "m.json:2:36: error: /parameters/shore_hardness/value: value 1000.25 of 'shore_hardness' "
          "is out of range; expected a "
          "value in [0, 1000] 1/m");
    CHECK(error_of("{\"name\": \"x\", \"axes\": {\"shore\": [\"soft\"]},\n \"parameters\": "
                   "{\"shore_hardness\": {\"min\": -1, \"max\": 2}}}") ==
          "m.json:2:36: error: /parameters/shore_hardness/min: range of 'shore_hardness' [-1, 2] "
          "leaves the range its node "
          "declares; expected within [0, 1000] 1/m");
    // A value outside the material's own (narrowed) range.
    CHECK(error_of("{\"name\": \"x\", \"axes\": {\"shore\": [\"soft\"]},\n \"parameters\": "
                   "{\"shore_hardness\": {\"value\": 8, \"min\": 1, \"max\": 2}}}") ==
          "m.json:2:36: error: /parameters/shore_hardness/value: value 8 of 'shore_hardness' is "
          "out of range; expected a "
          "value in [1, 2] 1/m");
    // Components of a vector are located one by one.
    CHECK(error_of("{\"name\": \"x\", \"parameters\": {\"absorb_coefficients\": {\"value\": [1, "
                   "200, 1]}}}") == "m.json:1:67: error: /parameters/absorb_coefficients/value/1: "
                                    "value 200 of 'absorb_coefficients' is out of range; "
                                    "expected a value in [0, 100] 1/m");
}

TEST_CASE("contradictory_constraints_are_errors", "[material]") {
    // A built-in rule: analytic normals need a closed-form wave model.
    CHECK(
        error_of(
            "{\"name\": \"x\", \"axes\": {\"normals\": [\"analytic\"], \"waves\": [\"flat\"]}}") ==
        "m.json:1:36: error: /axes/normals/0: contradictory constraints: normals=analytic is "
        "offered but no valid variant "
        "can use it: normals=analytic requires waves in {sum_of_sines, gerstner} (analytic normals "
        "are the derivatives of a "
        "closed-form wave model); got waves=flat");
    // The material's own rule leaves an offered choice unusable.
    CHECK(error_of("{\"name\": \"x\", \"axes\": {\"shore\": [\"hard\", \"soft\"], \"precision\": "
                   "[\"full\"]},\n \"rules\": "
                   "[{\"if\": \"shore=soft\", \"excludes\": {\"precision\": [\"full\"]}}]}") ==
          "m.json:1:42: error: /axes/shore/1: contradictory constraints: shore=soft is offered but "
          "no valid variant can use "
          "it: shore=soft excludes precision in {full}; got precision=full [m.json:2:46 "
          "/rules/0/excludes/precision]");
    // A rule about a choice not on offer, and a rule with no other choice.
    CHECK(error_of("{\"name\": \"x\", \"rules\": [{\"if\": \"fresnel=exact\", \"requires\": "
                   "{\"precision\": [\"full\"]}}]}") ==
          "m.json:1:62: error: /rules/0/requires/precision: rule about fresnel=exact, which the "
          "material does not offer "
          "(offered: schlick)");
    CHECK(error_of("{\"name\": \"x\", \"rules\": [{\"if\": \"fresnel\", \"requires\": "
                   "{\"precision\": [\"full\"]}}]}") ==
          "m.json:1:26: error: /rules/0/if: expected \"axis=choice\", got \"fresnel\"");
    CHECK(error_of("{\"name\": \"x\", \"rules\": [{\"if\": \"fresnel=schlick\", \"requires\": "
                   "{\"precision\": [\"full\"]}, "
                   "\"excludes\": {\"shore\": [\"soft\"]}}]}") ==
          "m.json:1:25: error: /rules/0: expected exactly one of 'requires' or 'excludes'");
}

TEST_CASE("builder_errors_without_a_file_still_say_what_was_expected", "[material]") {
    Diagnostics ds;
    CHECK_FALSE(MaterialBuilder("x").offer("fresnel", {"fancy"}).build(ds));
    REQUIRE(ds.size() == 1);
    CHECK(format_diagnostic(ds[0]) == "watergen: error: unknown fresnel choice 'fancy'; expected "
                                      "one of none, power, schlick, exact");
}

TEST_CASE("default_material_composes_with_its_values_and_ranges", "[material]") {
    const Material m = default_material();
    Variant v = default_variant();
    REQUIRE_FALSE(set_choice(v, "extinction", "absorb_scatter"));
    for (const char* axis : {"specular", "reflection", "refraction"})
        REQUIRE_FALSE(set_choice(v, axis, "none"));
    const WaterShader s = m.compose(v);
    REQUIRE_FALSE(has_errors(s.fragment.diagnostics()));
    const Parameter* k = s.fragment.find_parameter("absorb_coefficients");
    REQUIRE(k);
    CHECK(k->default_value == std::vector<double>{0.46, 0.09, 0.06});
    CHECK(k->min == 0.05);
    CHECK(k->max == 2.0);
    CHECK(s.preset == "tropical_ocean");
}

TEST_CASE("a_material_gives_an_array_parameter_every_element", "[material]") {
    // gerstner_wave_speeds is a float[8]: a value is eight numbers, each in range.
    const std::string waves = "{\"name\": \"x\", \"axes\": {\"waves\": [\"gerstner\"]}, "
                              "\"parameters\": {\"gerstner_wave_count\": {\"value\": 6}, "
                              "\"gerstner_wave_speeds\": {\"value\": ";
    CHECK(error_of(waves + "[1, 2, 3, 4, 5, 6, 7, 8]}}}").empty());
    CHECK(error_of(waves + "[1, 2, 3, 4]}}}")
              .find("parameter 'gerstner_wave_speeds' is a float[8]: expected 8 numbers, got 4") !=
          std::string::npos);
    CHECK(error_of(waves + "[1, 2, 3, 4, 5, 6, 7, 800]}}}")
              .find("value 800 of 'gerstner_wave_speeds'") != std::string::npos);
}
