// A small made-up comparison (no GPU): two 64x64 views, a reference variant and three others,
// with costs, time ratios and SPIR-V counts invented for the tests of the report writer.
#pragma once

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "watergen/eval/report/compare_report.h"

namespace watergen::test {

// How often `what` occurs in `text` (overlaps included).
inline std::size_t count_occurrences(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
        ++n;
    return n;
}

inline std::string read_file_text(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Sky-to-sea gradient: a blue-grey top half, a saturated green bottom half (linear 0.5 green
// shows as sRGB (0, 188, 0) and appears nowhere else in the report).
inline ImageRGBA32F synthetic_view(uint32_t size, float tint) {
    ImageRGBA32F img{size, size, std::vector<float>(std::size_t{size} * size * 4, 1.0f)};
    for (uint32_t y = 0; y < size; ++y) {
        for (uint32_t x = 0; x < size; ++x) {
            float* px = &img.rgba[(std::size_t{y} * size + x) * 4];
            const bool sea = y >= size / 2;
            px[0] = sea ? 0.0f : tint * (0.2f + 0.6f * float(x) / float(size - 1));
            px[1] = sea ? 0.5f : 0.3f;
            px[2] = sea ? 0.0f : 0.3f + 0.4f * float(y) / float(size - 1);
        }
    }
    return img;
}

// A ripple of +-amplitude on every channel: a small, spread-out error.
inline ImageRGBA32F with_ripple(ImageRGBA32F img, float amplitude) {
    for (uint32_t y = 0; y < img.height; ++y)
        for (uint32_t x = 0; x < img.width; ++x)
            for (int c = 0; c < 3; ++c)
                img.rgba[(std::size_t{y} * img.width + x) * 4 + c] +=
                    amplitude * std::sin(0.7f * float(x) + 1.3f * float(y) + float(c));
    return img;
}

// A white disc of `radius` around (cx, cy): a large, local error.
inline ImageRGBA32F with_blob(ImageRGBA32F img, uint32_t cx, uint32_t cy, uint32_t radius) {
    for (uint32_t y = 0; y < img.height; ++y) {
        for (uint32_t x = 0; x < img.width; ++x) {
            const double dx = double(x) - cx, dy = double(y) - cy;
            if (dx * dx + dy * dy > double(radius) * radius) continue;
            for (int c = 0; c < 3; ++c)
                img.rgba[(std::size_t{y} * img.width + x) * 4 + c] = 1.0f;
        }
    }
    return img;
}

inline CompareVariant synthetic_variant(std::string fresnel, std::string foam, bool reference,
                                        std::string relation, double cost, double time_ratio) {
    CompareVariant v;
    v.key = "fresnel=" + fresnel + ",foam=" + foam;
    v.choices = {{"fresnel", fresnel}, {"foam", foam}};
    v.reference = reference;
    v.relation = std::move(relation);
    v.cost = cost;
    v.time_ratio = time_ratio;
    v.time_ratio_lo = time_ratio * 0.97;
    v.time_ratio_hi = time_ratio * 1.03;
    v.spirv_instructions = static_cast<uint64_t>(cost * 8);
    return v;
}

// Views "overview" and "grazing"; variants: the reference (fresnel=exact, foam=none), schlick
// (ripple 0.01: approximates the reference), sprites (a blob at (44, 20) in both views: a
// different model; one NaN pixel at (3, 60) in "grazing") and schlick+sprites.
inline CompareReport synthetic_compare_report(uint32_t size = 64) {
    CompareReport r;
    r.title = "Synthetic comparison <fresnel & foam>";
    r.reference_key = "fresnel=exact,foam=none";
    r.timing_note = "median of 5 runs of 20 frames, lavapipe; A/A interval 1%";
    r.cost_note = "valgrind instructions per pixel, first draw";
    r.views = {{"overview", synthetic_view(size, 1.0f), ""},
               {"grazing", synthetic_view(size, 0.6f), ""}};
    r.variants = {
        synthetic_variant("exact", "none", true, "reference", 120, 1.0),
        synthetic_variant("schlick", "none", false, "approximates fresnel=exact", 100, 0.9),
        synthetic_variant("exact", "sprites", false, "different model", 140, 1.2),
        synthetic_variant("schlick", "sprites", false, "different model", 118, 1.1),
    };
    for (CompareVariant& v : r.variants) {
        for (const CompareView& view : r.views) {
            ImageRGBA32F img = view.reference;
            if (v.choices["fresnel"] == "schlick") img = with_ripple(img, 0.01f);
            if (v.choices["foam"] == "sprites") img = with_blob(img, 44, 20, 5);
            v.views.push_back({img, std::nullopt, std::nullopt});
        }
    }
    // One NaN pixel: the sprites variant breaks in the grazing view.
    r.variants[2].views[1].image.rgba[(std::size_t{60} * size + 3) * 4] =
        std::numeric_limits<float>::quiet_NaN();
    return r;
}

// One made-up caustics pass for the "Caustics passes" section: a 64x64 texture of 2 (sRGB grey
// 188 under the caustics tone map), a reference of 1.75, so the difference map is magma(0.5).
inline void add_synthetic_caustics_pass(CompareReport& r) {
    CausticsPassFigures p;
    p.name = "area_ratio, gerstner waves";
    p.texels = 64;
    p.pass.assign(64 * 64, 2.0);
    p.reference.assign(64 * 64, 1.75);
    p.max_abs = p.rmse = p.mean_difference = 0.25;
    p.mean = 2.0;
    p.reference_mean = 1.75;
    p.median_ms = 4.0;
    p.min_ms = 3.5;
    p.max_ms = 5.0;
    p.rounds = 3;
    p.ratio = p.ratio_lo = p.ratio_hi = 1.0;
    r.caustics_passes.push_back(p);
    r.caustics_note = "made up";
}

} // namespace watergen::test
