// Which views of the synthetic scene (scene_views.h) tell the choices of an axis apart: for
// every axis and every pair of its choices, two variants that differ in that axis alone are
// evaluated on the CPU in every view and their images compared. A pair no view separates is a
// pair of choices that look alike wherever the scene lets one look.
#pragma once

#include <string>
#include <vector>

#include "watergen/eval/image/image_io.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/water/variant.h"

namespace watergen {

// How far apart two images of one view are.
struct ImageDifference {
    double max_abs = 0;     // largest difference of a colour channel (linear)
    size_t pixels_over = 0; // pixels with a channel differing by more than the threshold
    size_t pixels = 0;      // in the image
};

struct ChoicePair {
    std::string axis, first, second;    // the two choices, in the axis' documentation order
    Variant base;                       // what both variants share (their `axis` is base's choice)
    std::vector<ImageDifference> views; // scene_views() order
};

struct ViewSeparation {
    uint32_t size = 0;
    double threshold = 0;          // the channel difference a pixel must exceed to count
    std::vector<ChoicePair> pairs; // axes() order, then pairs in documentation order
    std::string error;             // a variant failed to build or evaluate: "<key>: <what>"
    bool ok() const { return error.empty(); }
};

// The variant the pairs of `axis` vary from: `reference` with every other axis whose choice
// needs some choices of `axis` (analytic normals need closed-form waves; crest foam needs wave
// heights) moved to its last choice in documentation order that needs none, so every choice of
// `axis` is valid against it.
Variant separation_base(const Variant& reference, const std::string& axis);

// The CPU image of a variant over `scene`: float, or the half model (EvalPrecision::Half) for
// precision=half, whose shading GPUs that run mediump at 16 bits compute in binary16 (in float
// the two precisions are the same program). Empty with *error set when it fails.
ImageRGBA32F cpu_variant_image(const Variant& v, const SyntheticScene& scene, std::string* error);

// What:   for every axis of the registry and every pair of its choices, the images of the pair
//         (over separation_base(reference, axis)) in each view at size x size, compared.
// Cost:   one CPU evaluation per distinct variant and view (about 40 variants x 6 views; 4 ms
//         each at 96x96 on this project's 2-core machine) plus the views' scenes.
ViewSeparation measure_view_separation(const Variant& reference, uint32_t size, double threshold);

// One line per pair: axis, choices, then each view's max abs and the share of pixels over the
// threshold.
std::string view_separation_table(const ViewSeparation& s);

} // namespace watergen
