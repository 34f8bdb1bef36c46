// What a `watergen compare` compares, read from its flags and checked before any device is
// touched: the variants (a comma list per axis, --variant keys, or a material's variants and a
// scene's pruned set of them), the reference, the presets, the views (a scene's conformed to
// its facts, those it never shows left out) and where the report goes.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "watergen/eval/draw/draw_device.h"
#include "watergen/eval/measure/gpu_target.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/plan/scene_pruning.h"
#include "watergen/runtime/water_grid.h"
#include "watergen/water/presets.h"

namespace watergen {

// The command's flags.
struct CompareSpec {
    std::vector<std::string> axis_lists; // per axis (axes() order), "" or a comma list
    std::vector<std::string> keys;       // --variant
    std::string preset;                  // one, or a comma list: each view under each
    std::string reference = "gold";      // or a variant key, rendered on the GPU
    std::string out = "out/compare";
    std::string material, scene; // a material's variants, or a scene's pruned set of them
    std::string views;           // comma list; "": every view
    uint32_t size = 512, rounds = 40, draws = 3, cost_size = 64;
    bool cost = true, strict_half = false;
    // --target: cost targets (gpu_target.h); none: lavapipe. lavapipe's count is taken when it
    // is named (or none is) and `cost` holds; each AMD family's ACO statistics in any case.
    std::vector<std::string> targets;
    WaterGridDesc grid{}; // the grid mesh variants are drawn (and counted) over
};

// At most this many variants are compared.
inline constexpr size_t kMaxComparedVariants = 64;
// And at most this many variant pixels per view (variants x size^2): the interleaved timing
// holds every variant's render targets and image at once, so memory grows with variants x
// size^2 (views are streamed). 64 variants at 512x512, or 4 at 2048x2048, at the most.
inline constexpr uint64_t kMaxComparedPixels = uint64_t(64) * 512 * 512;

struct CompareSetup {
    CompareSpec spec;
    std::vector<Variant> variants;
    std::optional<Variant> reference; // nullopt: the gold, on the CPU
    const Preset* preset = nullptr;   // the variants are built with the first --preset
    // From --material / --scene: the variants composed by the material and, for a scene, folded
    // under its facts (plan) and drawn in the synthetic scene made to obey them.
    bool from_material = false;
    Material material;
    std::optional<ScenePlan> plan;
    std::vector<std::pair<std::string, SyntheticScene>> views; // "<view>@<preset>" for several
    std::vector<GpuTarget> gpu_targets;                        // the AMD families of --target
    bool lavapipe_cost = true;      // lavapipe among the targets (or none named)
    std::vector<std::string> notes; // "view X left out: why"
    Diagnostics diagnostics;        // of loading and planning the material and scene files
    std::string error;              // bad input ("" with diagnostics that hold the error)
    RunStatus status = RunStatus::Ok;
};

// The setup of `spec`, or its status BadInput with the error.
CompareSetup plan_compare(const CompareSpec& spec);

} // namespace watergen
