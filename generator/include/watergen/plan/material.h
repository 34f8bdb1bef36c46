// A material: which choices each axis offers, extra rules between them, parameter values and
// ranges, and the targets to emit. Written in C++ with MaterialBuilder, or in a JSON file that
// load_material() maps onto the same builder call by call, so both routes validate alike and
// produce identical output.
//
//   Material m = *MaterialBuilder("default")
//                     .offer("fresnel", {"schlick", "exact"})
//                     .parameter("shore_hardness", {1.0}).range("shore_hardness", 0.5, 4.0)
//                     .build(diagnostics);
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "watergen/ir/core/diagnostic.h"
#include "watergen/plan/json_source.h"
#include "watergen/plan/variant_space.h"
#include "watergen/water/water_shader.h"

namespace watergen {

// What a build writes per variant besides variant.json (see docs/user-guide.md "Build output").
enum class Target { Glsl, Hlsl, Spirv, Glsl330, Essl300, Msl, Reflection };
const std::vector<Target>& all_targets();
const char* to_string(Target t);
std::optional<Target> parse_target(const std::string& name);
std::string target_names(); // "glsl, hlsl, ..."

// Where a builder call came from: a JSON value of a description file, or C++ (no source).
struct SourceRef {
    const JsonSource* source = nullptr;
    std::string pointer; // JSON pointer of the value
    SourceRef child(const std::string& key) const { return {source, json_child(pointer, key)}; }
    SourceRef child(size_t index) const { return {source, json_child(pointer, index)}; }
    std::string where() const; // "file:line:col /pointer", or "" from C++
    Diagnostic error(const std::string& what) const;
};

struct ParameterSetting {
    std::optional<std::vector<double>> value; // replaces the node's default
    std::optional<double> min, max;           // narrows the node's range, every component
    std::string where;                        // of the setting, for explain
};

struct Material {
    std::string name, description;
    std::string file; // description file name, "" when built in C++
    VariantSpace space;
    std::string preset; // "" for none
    std::map<std::string, ParameterSetting> parameters;
    std::vector<Target> targets; // in all_targets() order
    // Parameters the offered nodes declare (name -> declaration), found by composing them.
    std::map<std::string, Parameter> declared;

    // The variant's shader, every graph of it (a mesh's vertex and tessellation stages as its
    // fragment) through settle_parameters(). `search`: the screen pass' surface search as chosen,
    // or converged (the exact surface a mesh is measured against). A scene's fixed values and
    // ranges come after, folded into every graph alike (fold_water_shader, plan/shader_fold.h).
    WaterShader compose(const Variant& v, SurfaceSearch search = SurfaceSearch::AsChosen) const;
    // The same for a shader serving several variants (water_shader.h, ShaderChoices).
    WaterShader compose(const ShaderChoices& choices,
                        SurfaceSearch search = SurfaceSearch::AsChosen) const;
    // The parameter pass, in place, on each graph of a water shader and of its companion passes,
    // so that one uniform set drives them all: the preset's defaults, then the material's values
    // and ranges. Returns the preset's parameters `g` declares with another size.
    std::vector<std::string> settle_parameters(Graph& g) const;
    // Parameter range after the material's narrowing.
    std::pair<double, double> range(const std::string& parameter) const;
};

class MaterialBuilder {
  public:
    explicit MaterialBuilder(std::string name, SourceRef at = {});

    MaterialBuilder& description(std::string text);
    // Offers these choices on the axis (the axes never offered keep their default choice).
    MaterialBuilder& offer(const std::string& axis, const std::vector<std::string>& choices,
                           SourceRef at = {});
    MaterialBuilder& offer_all(const std::string& axis, SourceRef at = {});
    // axis=choice needs / cannot have other_axis in other_choices.
    MaterialBuilder& requires_choice(const std::string& axis, const std::string& choice,
                                     const std::string& other_axis,
                                     const std::vector<std::string>& other_choices, std::string why,
                                     SourceRef at = {});
    MaterialBuilder& excludes_choice(const std::string& axis, const std::string& choice,
                                     const std::string& other_axis,
                                     const std::vector<std::string>& other_choices, std::string why,
                                     SourceRef at = {});
    MaterialBuilder& preset(const std::string& name, SourceRef at = {});
    MaterialBuilder& parameter(const std::string& name, const std::vector<double>& value,
                               SourceRef at = {});
    MaterialBuilder& range(const std::string& name, double min, double max, SourceRef at = {});
    MaterialBuilder& targets(const std::vector<std::string>& names, SourceRef at = {});

    // Validates everything (unknown names, sizes, ranges, contradictory rules) in a fixed order
    // and returns the material, or nullopt with the first error in `diagnostics`.
    std::optional<Material> build(Diagnostics& diagnostics) const;

  private:
    struct Offer {
        std::string axis;
        std::vector<std::string> choices;
        bool all = false;
        SourceRef at;
    };
    struct RuleCall {
        Rule rule;
        SourceRef at;
    };
    struct ParameterCall {
        std::string name;
        std::optional<std::vector<double>> value;
        std::optional<std::pair<double, double>> range;
        SourceRef at;
    };
    std::string name_;
    SourceRef name_at_;
    std::string description_;
    std::vector<Offer> offers_;
    std::vector<RuleCall> rules_;
    std::optional<std::pair<std::string, SourceRef>> preset_;
    std::vector<ParameterCall> parameters_;
    std::optional<std::pair<std::vector<std::string>, SourceRef>> targets_;

    // The steps of build(), in its order (material.cpp says what each settles).
    std::optional<Diagnostic> check_name(Material& m) const;
    std::optional<Diagnostic> check_offers(Material& m) const;
    std::optional<Diagnostic> check_rules(Material& m) const;
    std::optional<Diagnostic> check_usable(Material& m) const;
    std::optional<Diagnostic> check_preset(Material& m) const;
    std::optional<Diagnostic> check_parameters(Material& m) const;
    std::optional<Diagnostic> check_values(Material& m) const;
    std::optional<Diagnostic> check_targets(Material& m) const;
    static std::optional<Diagnostic> offered_choices(const Offer& o,
                                                     std::vector<std::string>& choices);
    static std::optional<Diagnostic> apply_setting(const ParameterCall& call, const Parameter& p,
                                                   ParameterSetting& s);
    SourceRef offered_at(size_t axis, const std::string& choice) const;
};

// Reads a material description (format: docs/user-guide.md "Material files";
// material_file.cpp). Errors name the file, line, column and JSON path, and what was expected.
std::optional<Material> load_material(const std::filesystem::path& path, Diagnostics& diagnostics);
std::optional<Material> parse_material(const JsonSource& source, Diagnostics& diagnostics);

// The first mistake in a project's registered nodes (axis_registry.h), found by composing the
// default variant with each choice of every axis in turn (those the constraints allow): an
// error composing a node's IR, or a parameter two authors define differently (both
// definitions named). nullopt when nothing is registered. A project's generator checks this at
// start, so a redefinition is refused even where the two nodes never meet in one variant.
std::optional<Diagnostic> check_registered_nodes();

// The built-in default material (default_material.cpp; examples/materials/default.json is the
// same in JSON, and a test builds both and compares them).
Material default_material();

// A material of a preset alone (nullptr: none), with no parameter settings: variants named by
// their choices are built with the preset (build_variant), and a build of this material ships
// the caustics pass they read.
Material preset_material(const Preset* preset);

} // namespace watergen
