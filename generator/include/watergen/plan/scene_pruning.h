// From scene facts to what a build needs: which variants of a material a scene can reach
// (the rest are not generated), which parameters it fixes, what ranges it guarantees (the
// fold pass turns those into constants and removed terms), and which targets its platforms
// need. Every decision keeps the scene fact behind it, for `watergen explain`.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "watergen/ir/fold/ir_fold.h"
#include "watergen/plan/material.h"
#include "watergen/plan/scene_file.h"
#include "watergen/plan/variant_list.h"
#include "watergen/water/axis_registry.h"

namespace watergen {

// Why a scene cannot use a choice.
struct Exclusion {
    std::string axis, choice;
    std::string reason; // "no shoreline: shore foam never shows"
    std::string where;  // "open_ocean.json:4:3 /shoreline"
};

// The first choice of `v` the scene rules out (by the scene needs of the registry's choices,
// in SceneFact order, then axis order), or nullopt when it reaches v. Facts that read parameters
// (BottomLit: the extinction model's coefficients) are checked only with `bounds`.
std::optional<Exclusion> scene_excludes(const SceneFacts& scene, const Variant& v,
                                        const ParameterBounds* bounds = nullptr);

// A material's parameter ranges with the scene's fixed values in place of the fixed ones.
// Keeps references to both.
ParameterBounds parameter_bounds(const Material& material,
                                 const std::map<std::string, std::vector<double>>& fixed);

// Material variants a scene does not reach for one reason.
struct SkippedGroup {
    Exclusion exclusion;
    size_t variants = 0;
    std::string text() const; // "precision=half: the scene targets precision full
                              // [open_ocean.json:11:3 /precision]"
};

struct ScenePlan {
    SceneFacts scene;
    FoldFacts facts;      // for fold_graph; scene facts about quantities keyed by handle
    VariantList variants; // reached, sorted by key; a byte an axis
    size_t skipped = 0;   // material variants the scene does not reach
    // One per reason, sorted by text(). Which variant has which reason is not kept (8 bytes a
    // variant per scene, most of a build's plan for the full space): scene_excludes gives it.
    std::vector<SkippedGroup> skipped_groups;
    std::vector<Target> targets; // material targets its platforms need, all_targets() order
    std::map<std::string, std::vector<double>> fixed; // parameters that become constants
};

// Plans one scene against a material. Errors (exit 2): a fixed parameter the material's
// nodes do not read, of the wrong size or out of range; time fixed with animated waves; a
// scene that reaches no variant or needs no target the material emits ("needs nothing").
std::optional<ScenePlan> plan_scene(const Material& material, const SceneFacts& scene,
                                    Diagnostics& diagnostics);

// The facts every build assumes about its inputs (uv in [0, 1], finite scene textures within
// the world's extent), and the material's parameter ranges; plan_scene adds the scene's.
FoldFacts base_facts(const Material& material);

} // namespace watergen
