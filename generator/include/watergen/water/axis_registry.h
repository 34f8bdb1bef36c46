// The axis registry: every axis of the water pass and, per choice, everything the toolkit
// derives from it. Each axis file (water/nodes/<axis>.cpp) declares its choices once, in one
// table; the axis list, variant keys, the node catalog, the composition of the water pass, the
// built-in rules of the variant space, scene pruning, `--help` and the user guide's axis table
// are all read from here. Adding a choice to an axis touches its axis file only.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "watergen/ir/core/source_location.h"
#include "watergen/water/node_catalog.h"

namespace watergen {

struct Surface;

// Scene facts a choice can depend on, in the order scene pruning checks them (plan/scene_pruning).
enum class SceneFact {
    Shoreline,        // water meets land somewhere in view
    ReflectionSource, // the engine provides the reflection source named by SceneNeed::value
    SunAboveHorizon,  // the sun rises above the horizon at some time
    BottomInView,     // the refracted scene shows the bottom somewhere
    BottomLit,        // sunlight reaches the bottom (the variant's extinction, the scene's depth)
    Precision,        // the scene targets the precision named by SceneNeed::value (or any)
    SceneInput,       // the engine gives the scene's position as SceneNeed::value (or either)
    CameraNear,       // the camera comes close enough to the water for tessellation to refine it
};

// What a choice needs from a scene; a scene without it never shows the choice.
struct SceneNeed {
    SceneFact fact = SceneFact::Shoreline;
    // ReflectionSource: "cubemap", "planar" or "horizon_map"; Precision: "full" or "half";
    // SceneInput: "position_texture" or "depth_buffer".
    std::string value{};
    std::string consequence{}; // ends the reason: "no shoreline, so <consequence>"; "" for none
};

// A parameter's range for scene pruning: the scene's fixed value(s), else the material's range;
// (lowest, highest) over its components.
using ParameterBounds = std::function<std::pair<double, double>(const std::string& parameter)>;

// The largest share of the sunlight entering the water that reaches `depth` m below the surface,
// by an extinction model with its parameters anywhere in `bounds` (SceneFact::BottomLit).
using SunlightAtDepth = std::function<double(const ParameterBounds& bounds, double depth)>;

// axis=choice is valid only with `axis` in `choices`.
struct ChoiceRequirement {
    std::string axis{};
    std::vector<std::string> choices{}; // documentation order of `axis`
    std::string why{};                  // "crest foam needs wave heights"
    // `choices` lists the excluded ones instead; resolved when the registry is frozen.
    bool all_but = false;
};
// Every choice of `axis` except `excluded` (resolved once every axis is known).
ChoiceRequirement every_choice_but(const std::string& axis, std::vector<std::string> excluded,
                                   const std::string& why);

// The choice's feature node on its own: the catalog entry "<axis>.<choice>" the probe runs.
struct ChoiceNode {
    std::vector<NodeInput> inputs{};
    std::function<Expr(Graph&, const std::vector<Expr>&)> build{};
    std::string note{}; // appended to the catalog description, e.g. textures the node reads
};

struct ChoiceInfo {
    std::string name{};         // e.g. "schlick"
    std::string seed{};         // article it comes from, e.g. "000"
    std::string description{};  // one line for --help, reports and the node catalog
    bool gold = false;          // the reference the cheaper choices are measured against
    std::string approximates{}; // the choice of the same axis this one approximates, or ""
    std::optional<ChoiceNode> node{};
    // What the choice does to the surface (water_shader.cpp runs the axes in order); empty:
    // leaves it as it is (foam=none, shore=hard, precision: the skeleton's scope).
    std::function<void(Surface&)> compose{};
    std::vector<SceneNeed> scene_needs{};
    std::vector<ChoiceRequirement> requirements{};
    // Extinction choices: how much sunlight their model lets reach a depth; unset: all of it.
    SunlightAtDepth sunlight_at_depth{};
    // Where a project registered the choice (register_choice); empty for watergen's own. Its
    // composition declares and reports as this author (ir.h, Author).
    Author author{};
};

// A choice with its own feature node: `node` is its catalog entry, `compose` what it does to the
// surface. Each axis file wraps this once with the inputs and surface fields of its nodes.
ChoiceInfo feature_choice(ChoiceInfo info, ChoiceNode node, std::function<void(Surface&)> compose);

// The same for a node taking one Expr, or a struct of Exprs in member order: the catalog entry
// passes it the values of `inputs`, in order.
template <class Inputs, std::size_t N>
ChoiceInfo feature_choice(ChoiceInfo info, const NodeInput (&inputs)[N],
                          Expr (*node)(Graph&, Inputs), std::function<void(Surface&)> compose) {
    auto build = [node](Graph& g, const std::vector<Expr>& in) {
        return [&]<std::size_t... I>(std::index_sequence<I...>) {
            return node(g, std::remove_cvref_t<Inputs>{in[I]...});
        }
        (std::make_index_sequence<N>{});
    };
    return feature_choice(std::move(info), ChoiceNode{{inputs, inputs + N}, build},
                          std::move(compose));
}

struct AxisInfo {
    std::string name{}; // e.g. "fresnel"
    std::string default_choice{};
    std::vector<ChoiceInfo> choices{}; // in documentation order
    // Catalog nodes of the axis that are not choices ("waves.gerstner.normal"); names are full.
    std::vector<CatalogNode> extra_nodes{};
    // An axis a project registers (register_axis): composed right after this axis (and the
    // skeleton's step that follows it: after normals, V and N.V; after specular, the Fresnel
    // blend into `color`). Empty for watergen's axes, whose order is the registry's.
    std::string compose_after{};
    Author author{}; // where a project registered the axis; empty for watergen's own
    // false: a variant key and file stem leave the axis out at its default choice, so an axis
    // added to watergen later renames no variant that existed before it (keys, hashes, file
    // names and an engine's caches stay as they were). scene_input is such an axis.
    bool keyed_at_default = true;
    // Always a permutation (one shader per choice, never a switch in a shared shader): an axis
    // that changes the types of all the shading (precision), the resources a pass binds
    // (scene_input: a depth buffer or a position texture) or the stages before the fragment
    // (geometry).
    bool permutation_only = false;
};

// Whether a key or file stem spells `axis` with `choices` offered (keyed_at_default).
bool spelled_in_key(const AxisInfo& axis, const std::vector<std::string>& choices);
bool spelled_in_key(const AxisInfo& axis, const std::string& choice); // a variant's one choice

// Every axis in fixed order; the order of a variant key. The first call freezes the registry.
const std::vector<AxisInfo>& axes();
const AxisInfo* find_axis(const std::string& name);
const ChoiceInfo* find_choice(const AxisInfo& axis, const std::string& name);

// A project's own nodes, added without editing watergen (docs/authoring.md). Registration
// happens before the registry's first use (axes()), typically from WATERGEN_REGISTER_NODES at
// static initialisation of the project's generator (watergen_add_generator); `where` is the
// call's file and line, which the choice's diagnostics and name clashes then carry.
//
// Adds a choice at the end of an existing axis. Returns why not (after the first call to
// axes(), an unknown axis, a name in use or not a lower-case identifier), and records the
// same in registration_errors().
std::optional<std::string> register_choice(const std::string& axis, ChoiceInfo choice,
                                           SourceLocation where = SourceLocation::current());
// Adds a whole axis: its choices, its default, and its place in composition
// (AxisInfo::compose_after, checked when the registry freezes). It comes after watergen's axes
// in a variant key, in registration order. Errors as for register_choice.
std::optional<std::string> register_axis(AxisInfo axis,
                                         SourceLocation where = SourceLocation::current());
// Every registration that failed, with its file and line: a generator stops on them before
// doing anything (the CLI exits 2).
const Diagnostics& registration_errors();
// The axes in the order the water pass composes them (water_shader.cpp): watergen's, with each
// registered axis right after its compose_after. Freezes the registry like axes().
const std::vector<std::string>& composition_order();

// Runs the choice's composition on the surface; an unknown choice records a diagnostic.
void compose_choice(Surface& s, const std::string& axis, const std::string& choice);
// Composes several choices of one axis, each in its own case of a switch on the axis' selector
// parameter (selector_parameter(), water_shader.h: a specialization constant when `specialized`,
// else a uniform-block member); the surface's fields afterwards are the selected case's
// (axis_switch.cpp).
void compose_switch(Surface& s, const std::string& axis, const std::vector<std::string>& choices,
                    bool specialized);

// The --<axis> option's help: default, then one line per choice with gold, what it approximates,
// the choices of other axes it needs, and its seed.
std::string axis_help(const AxisInfo& axis);
// The axis table of docs/user-guide.md ("Axes"): "| axis | choices |" with each choice's seed
// and gold mark.
std::string axes_markdown_table();

} // namespace watergen

// Registers a project's nodes at static initialisation, before main:
//   WATERGEN_REGISTER_NODES(register_fog) { watergen::register_axis(fog_axis()); }
#define WATERGEN_REGISTER_NODES(function)                                                          \
    static void function();                                                                        \
    [[maybe_unused]] static const bool function##_registered = (function(), true);                 \
    static void function()
