#include "watergen/water/nodes/caustics.h"

#include "axis_tables.h"
#include "watergen/water/frame.h"
#include "watergen/water/nodes/waves.h"
#include "watergen/water/surface.h"

namespace watergen {

TextureInput caustics_tile_texture() {
    return {"caustics_tile", Type::Texture2D,
            "caustics intensity in r (1: flat water); periodic tile, texel k at k / (n - 1)",
            "caustics"};
}

TextureInput caustics_map_texture() {
    return {"caustics_map", Type::Texture2D,
            "caustics intensity in r (1: flat water) over the bottom window caustics_window",
            "caustics"};
}

Parameter caustics_window() {
    return {.name = "caustics_window",
            .type = Type::Vec3,
            .default_value = {-5.0, -5.0, 10.0},
            .min = -1e7,
            .max = 1e7,
            .unit = "m",
            .seed = "002",
            .origin = "caustics",
            .host = {HostRule::FramePointXZ, {}}};
}

Parameter caustics_map_texels() {
    return {.name = "caustics_map_texels",
            .type = Type::Float,
            .default_value = {64.0},
            .min = 1.0,
            .max = 16384.0,
            .unit = "texels",
            .seed = "002",
            .origin = "caustics"};
}

Expr caustics_lit(Graph& g, Expr refracted, Expr intensity) {
    // 0 leaves the bottom as the scene lit it; 1 applies the texture's intensity as it is.
    Expr strength = uniform(g, {.name = "caustics_strength",
                                .type = Type::Float,
                                .default_value = {1.0},
                                .max = 4.0,
                                .seed = "002",
                                .origin = "caustics"});
    return named(refracted * mix(constant(g, 1.0), intensity, strength), "caustics_lit");
}

Expr caustics_texture_intensity(Graph& g, Expr bottom_xz) {
    // Crest tiles one caustics texture over the bottom; its world size is artistic (10 m here).
    Expr size = uniform(g, {.name = "caustics_tile_size",
                            .type = Type::Float,
                            .default_value = {10.0},
                            .min = 1e-3,
                            .max = 1e4,
                            .unit = "m",
                            .origin = "caustics"});
    // bottom_xz is in the frame (frame.h): the host adds c / size mod 1 (0 without an eye).
    Expr offset = uniform(g, tile_offset("caustics_tile_offset", "caustics_tile_size"));
    Expr texels = uniform(g, {.name = "caustics_tile_texels",
                              .type = Type::Float,
                              .default_value = {64.0},
                              .min = 2.0,
                              .max = 16384.0,
                              .unit = "texels",
                              .origin = "caustics"});
    FullPrecisionScope geometry(g); // positions up to 1e5 m overflow binary16
    Expr uv = tile_coordinate(bottom_xz / size + offset, texels);
    // Level 0: fract makes implicit derivatives jump at the tile's seams.
    return named(sample_level(texture(g, caustics_tile_texture()), uv, constant(g, 0.0)).x(),
                 "caustics_intensity");
}

namespace {

// Where the bottom point falls in the map, and whether inside the window.
struct MapPoint {
    Expr uv;
    Expr inside;
};

MapPoint map_point(Graph& g, Expr bottom_xz) {
    FullPrecisionScope geometry(g);
    Expr window = uniform(g, caustics_window());
    Expr uv = named((bottom_xz - vec2(window.x(), window.y())) / window.z(), "caustics_uv");
    Expr inside = uv.x() >= 0.0 && uv.x() <= 1.0 && uv.y() >= 0.0 && uv.y() <= 1.0;
    return {uv, inside};
}

Expr map_texel(Graph& g, Expr uv) {
    return sample_level(texture(g, caustics_map_texture()), uv, constant(g, 0.0)).x();
}

} // namespace

Expr caustics_area_ratio_intensity(Graph& g, Expr bottom_xz) {
    const MapPoint p = map_point(g, bottom_xz);
    return named(select(p.inside, map_texel(g, p.uv), constant(g, 1.0)), "caustics_intensity");
}

Expr caustics_photon_splat_intensity(Graph& g, Expr bottom_xz) {
    const MapPoint p = map_point(g, bottom_xz);
    Expr texels = uniform(g, caustics_map_texels());
    Expr half_texel = 0.5 / texels;
    Expr sum = map_texel(g, p.uv + vec2(-half_texel, -half_texel)) +
               map_texel(g, p.uv + vec2(half_texel, -half_texel)) +
               map_texel(g, p.uv + vec2(-half_texel, half_texel)) +
               map_texel(g, p.uv + vec2(half_texel, half_texel));
    return named(select(p.inside, sum * 0.25, constant(g, 1.0)), "caustics_intensity");
}

namespace {

using IntensityNode = Expr (*)(Graph&, Expr);

// The catalog node: the lit bottom from the refracted colour and the bottom point.
// In 32 bits whatever the precision axis: positions, the texel, the mix and the product are a
// few instructions, and the bottom point in binary16 (1/64 m at 10 m) would move the sample by
// a fraction of a texel.
template <IntensityNode Intensity> Expr caustics_node(Graph& g, const CausticsInputs& in) {
    FullPrecisionScope full(g);
    return caustics_lit(g, in.refracted, Intensity(g, in.bottom_xz));
}

template <IntensityNode Intensity> ChoiceInfo caustics_choice(ChoiceInfo info) {
    // Caustics are sunlight on the bottom: a scene whose sun never rises, that shows no bottom,
    // or whose water is deeper than its extinction lets the sunlight reach, has none.
    info.scene_needs = {{SceneFact::SunAboveHorizon, "", "there are no caustics"},
                        {SceneFact::BottomInView, "", "caustics never show"},
                        {SceneFact::BottomLit, "", "there are no caustics"}};
    const std::string origin = "caustics." + info.name;
    return feature_choice(
        std::move(info), {{"color", Type::Vec3}, {"xz", Type::Vec2}}, &caustics_node<Intensity>,
        [origin](Surface& s) {
            OriginScope scope(s.g, origin);
            // The swizzle too: a relaxed xz would round positions to binary16.
            FullPrecisionScope full(s.g);
            s.refracted = caustics_node<Intensity>(s.g, {s.refracted, s.scene_pos.xz()});
        });
}

ChoiceRequirement caustics_pass_requirement() {
    return {"waves",
            {"sum_of_sines", "gerstner"},
            "the caustics pass traces the sunlight through a closed-form wave model"};
}

} // namespace

AxisInfo caustics_axis() {
    return {"caustics",
            "none",
            {
                {.name = "none", .description = "no caustics: the bottom as the scene lit it"},
                caustics_choice<&caustics_texture_intensity>(
                    {.name = "texture",
                     .description = "a tiled caustics texture, repeated every caustics_tile_size "
                                    "(Crest's stand-in: no pass, any waves)"}),
                caustics_choice<&caustics_area_ratio_intensity>(
                    {.name = "area_ratio",
                     .description = "the area_ratio caustics pass's map over caustics_window "
                                    "(Evan Wallace's method, as Unity HDRP's water ships it)",
                     .requirements = {caustics_pass_requirement()}}),
                caustics_choice<&caustics_photon_splat_intensity>(
                    {.name = "photon_splat",
                     .seed = "002",
                     .description = "the photon_splat pass's map over caustics_window, filtered "
                                    "by a 4-tap box at +-0.5 texel (the seed filters its photons)",
                     .requirements = {caustics_pass_requirement()}}),
            }};
}

} // namespace watergen
