#include "watergen/water/nodes/foam.h"

#include <cmath>
#include <numbers>

#include "axis_tables.h"
#include "watergen/water/frame.h"
#include "watergen/water/nodes/extinction.h"
#include "watergen/water/surface.h"

namespace watergen {

namespace {

Parameter foam_existence() {
    // 000: e.x depth where shore foam starts to fade, e.y where it is gone, e.z crest height.
    return {.name = "foam_existence",
            .type = Type::Vec3,
            .default_value = {0.45, 4.35, 1.5},
            .max = 100.0,
            .unit = "m",
            .seed = "000"};
}

Parameter foam_pattern_scale() {
    // 000 samples its foam photo at the surface point; scale and drift are chosen: 10 m per
    // pattern tile (the shortest wavelength is 2 m), drifting a tile in about 5 minutes.
    return {.name = "foam_pattern_scale",
            .type = Type::Float,
            .default_value = {0.1},
            .min = 1e-4,
            .max = 100.0,
            .unit = "1/m",
            .seed = "000"};
}

// Turns relaxed precision off for geometry, whatever scope the caller is in.
class UnrelaxedScope {
  public:
    explicit UnrelaxedScope(Graph& g) : g_(g), previous_(g.relaxed()) { g.set_relaxed(false); }
    ~UnrelaxedScope() { g_.set_relaxed(previous_); }
    UnrelaxedScope(const UnrelaxedScope&) = delete;
    UnrelaxedScope& operator=(const UnrelaxedScope&) = delete;

  private:
    Graph& g_;
    bool previous_;
};

Expr blend_foam(Graph& g, const FoamInputs& in, Expr coverage) {
    // 000 multiplies a greyscale foam photo by the coverage; tinted and blended here so the
    // colour stays between the water colour and the foam colour.
    Expr foam_color = uniform(g, {.name = "foam_color",
                                  .type = Type::Vec3,
                                  .default_value = {1.0, 1.0, 1.0},
                                  .max = 1e3,
                                  .seed = "000"});
    return named(mix(in.color, foam_color * in.pattern, coverage), "foam_rgb");
}

} // namespace

TextureInput foam_pattern_texture() {
    return {"foam_pattern", Type::Texture2D, "foam pattern, periodic smooth sines, value in r",
            "foam"};
}

double foam_pattern_value(double u, double v) {
    // Integer wave vectors keep it periodic; the highest has |k| = 5 cycles per period (2 m at
    // the default 10 m tile), so it is smooth at the texel scale. |sum| <= 1.
    const double tau = 2.0 * std::numbers::pi;
    const double s = 0.35 * std::sin(tau * (2 * u + v)) + 0.25 * std::sin(tau * (3 * v - u) + 1.1) +
                     0.2 * std::sin(tau * (4 * u - 2 * v) + 2.3) +
                     0.2 * std::sin(tau * (3 * u + 4 * v) + 0.6);
    return kFoamPatternMean + 0.4 * s;
}

Expr foam_pattern_coordinate(Graph& g, Expr world_xz, Expr time) {
    Expr scale = uniform(g, foam_pattern_scale());
    const Parameter drift_parameter{.name = "foam_pattern_drift",
                                    .type = Type::Vec2,
                                    .default_value = {0.003, 0.002},
                                    .min = -1.0,
                                    .max = 1.0,
                                    .unit = "1/s",
                                    .seed = "000"};
    Expr drift = uniform(g, drift_parameter);
    // With the scene's clock the position is in the frame (frame.h): the host adds c scale +
    // drift t mod 1.
    Expr offset = is_scene_clock(time) ? scroll_offset(g, "foam_pattern_offset",
                                                       foam_pattern_scale(), drift_parameter)
                                       : drift * time;
    Expr wrapped = fract(world_xz * scale + offset);
    const double n = kFoamPatternSize;
    return named((wrapped * (n - 1.0) + 0.5) / n, "foam_uv");
}

Expr foam_pattern_filtered(Graph& g, Expr pattern, Expr footprint) {
    // Cycles of the finest sine per pixel: past 1/2 (Nyquist) the pattern would alias into
    // noise, and positions far away differ between GPU and CPU by more than a texel.
    Expr cycles_per_pixel = footprint * uniform(g, foam_pattern_scale()) * kFoamPatternMaxCycles;
    Expr aliased = named(saturate(4.0 * cycles_per_pixel - 1.0), "foam_aliasing");
    return named(mix(pattern, constant(g, kFoamPatternMean), aliased), "foam_pattern");
}

Expr foam_shore_coverage(Graph& g, Expr depth) {
    Expr e = uniform(g, foam_existence());
    // Negative depth (scene a hair above the plane) counts as the shoreline.
    Expr past_start = max(depth, 0.0) - e.x();
    Expr fade = saturated_ratio(past_start, e.y() - e.x()); // no division when e.y <= e.x
    return named(select(past_start < 0.0, constant(g, 1.0), 1.0 - fade), "shore_foam");
}

Expr foam_crest_coverage(Graph& g, Expr height) {
    Expr e = uniform(g, foam_existence());
    // 000's Hmax; it gives no value: twice e.z, so crest foam grows over the top half of 3 m waves.
    Expr h_max = uniform(g, {.name = "foam_max_height",
                             .type = Type::Float,
                             .default_value = {3.0},
                             .max = 100.0,
                             .unit = "m",
                             .seed = "000"});
    Expr span = h_max - e.z();
    // 000 draws no crest foam unless Hmax > e.z; saturated_ratio alone would turn a
    // non-positive span into foam everywhere above e.z.
    return named(select(span > 0.0, saturated_ratio(height - e.z(), span), constant(g, 0.0)),
                 "crest_foam");
}

Expr foam_shore(Graph& g, const FoamInputs& in) {
    OriginScope scope(g, "foam.shore");
    return blend_foam(g, in, foam_shore_coverage(g, in.depth));
}

Expr foam_crest(Graph& g, const FoamInputs& in) {
    OriginScope scope(g, "foam.crest");
    return blend_foam(g, in, foam_crest_coverage(g, in.height));
}

Expr foam_both(Graph& g, const FoamInputs& in) {
    OriginScope scope(g, "foam.both");
    Expr f = saturate(foam_shore_coverage(g, in.depth) + foam_crest_coverage(g, in.height));
    return blend_foam(g, in, named(f, "foam_coverage"));
}

namespace {

using FoamNode = Expr (*)(Graph&, const FoamInputs&);

// Blends the foam of `node` into the composed colour: the pattern at the surface point, its
// height above the water level and the water depth.
void compose_foam(Surface& s, FoamNode node, const std::string& origin) {
    OriginScope scope(s.g, origin);
    Expr coordinate, height, footprint;
    {
        // Positions up to 1e5 m and times up to 86400 s overflow binary16: geometry stays 32-bit.
        UnrelaxedScope geometry(s.g);
        Expr xz = s.surface_point.xz();
        coordinate = foam_pattern_coordinate(s.g, xz, s.time);
        height = named(s.surface_point.y() - s.level, "wave_height");
        footprint = named(max(length(ddx(xz)), length(ddy(xz))), "foam_footprint");
    }
    // Explicit level 0: the single-level texture needs no derivatives, which fract breaks.
    Expr raw = named(
        sample_level(texture(s.g, foam_pattern_texture()), coordinate, constant(s.g, 0.0)).x(),
        "foam_texel");
    s.color = node(s.g, {s.color, foam_pattern_filtered(s.g, raw, footprint), s.depth, height});
}

ChoiceInfo foam_choice(ChoiceInfo info, FoamNode node) {
    const std::string origin = "foam." + info.name;
    return feature_choice(std::move(info),
                          {{"color", Type::Vec3},
                           {"pattern", Type::Float},
                           {"depth", Type::Float},
                           {"height", Type::Float}},
                          node, [node, origin](Surface& s) { compose_foam(s, node, origin); });
}

SceneNeed shoreline_need() {
    return {SceneFact::Shoreline, "", "shore foam never shows"};
}

ChoiceRequirement wave_heights_requirement() {
    return every_choice_but("waves", {"flat"}, "crest foam needs wave heights");
}

} // namespace

AxisInfo foam_axis() {
    return {"foam",
            "none",
            {
                {.name = "none", .description = "no foam"},
                foam_choice({.name = "shore",
                             .seed = "000",
                             .description = "foam band along the shoreline by depth",
                             .scene_needs = {shoreline_need()}},
                            &foam_shore),
                foam_choice({.name = "crest",
                             .seed = "000",
                             .description = "foam on wave crests by height",
                             .requirements = {wave_heights_requirement()}},
                            &foam_crest),
                foam_choice({.name = "both",
                             .seed = "000",
                             .description = "shore and crest foam",
                             .scene_needs = {shoreline_need()},
                             .requirements = {wave_heights_requirement()}},
                            &foam_both),
            }};
}

} // namespace watergen
