#include "watergen/eval/draw/variant_caustics.h"

#include "watergen/eval/draw/caustics_bottom.h"
#include "watergen/water/nodes/caustics.h"

namespace watergen {

namespace {

// The r channel of a texture, row-major.
std::vector<double> intensities(const TextureData& t) {
    std::vector<double> out;
    for (size_t p = 0; p < t.rgba.size(); p += 4)
        out.push_back(t.rgba[p]);
    return out;
}

nlohmann::ordered_json pass_json(const SceneCausticsPass& p) {
    return {
        {"method", to_string(p.method)},
        {"wave_model", p.wave_model},
        {"depth_m", kSceneCausticsDepth},
        {"margin_m", kSceneCausticsMargin},
        {"cells_per_texel", default_cells_per_texel(p.method)},
        {"glsl",
         {{"pipeline_ms", p.glsl.pipeline_ms},
          {"first_draw_ms", p.glsl.first_draw_ms},
          {"steady_draw_ms", p.glsl.steady_draw_ms},
          {"draw_ms", p.glsl.draw_ms}}},
        {"mean", p.mean},
        {"reference",
         {{"what", "CPU photon reference (caustics_reference), the same values"},
          {"photons_per_texel", kSceneCausticsReferencePhotons * kSceneCausticsReferencePhotons},
          {"mean", p.reference_mean}}},
        {"vs_reference",
         {{"max_abs", p.vs_reference.max_abs},
          {"rmse", p.vs_reference.rmse},
          {"mean_difference", p.vs_reference.mean_difference}}},
        {"glsl_vs_hlsl_max_abs", p.glsl_vs_hlsl}};
}

} // namespace

bool has_caustics(const Variant& variant) {
    return variant.choice("caustics") != "none";
}

RenderCaustics prepare_render_caustics(VulkanRunner& runner, const Variant& variant,
                                       const VariantBuild& water, SyntheticScene& scene,
                                       uint32_t timed_draws, const Preset* preset) {
    RenderCaustics out;
    out.choice = variant.choice("caustics");
    if (const auto method = caustics_pass_method(out.choice)) {
        const CausticsPassBuild build =
            build_caustics_pass_files(preset_material(preset), {*method, variant.choice("waves")});
        out.pass = draw_scene_caustics_pass(runner, build, scene,
                                            scene_caustics_texels(water, scene), timed_draws);
        if (!out.pass->ok()) {
            out.error = out.pass->error;
            return out;
        }
        use_caustics_pass(scene, *out.pass);
    }
    const bool tile = out.choice == "texture";
    const TextureData& t =
        scene.textures.at(tile ? caustics_tile_texture().name : caustics_map_texture().name);
    out.texture = intensities(t);
    out.texels = t.width;
    out.lit_bottom = caustics_lit_bottom(out.choice, scene, &out.error);
    return out;
}

nlohmann::ordered_json render_caustics_json(const RenderCaustics& c) {
    nlohmann::ordered_json j;
    j["choice"] = c.choice;
    j["texture"] = {{"name", c.pass ? caustics_map_texture().name : caustics_tile_texture().name},
                    {"texels", c.texels},
                    {"made_by", c.pass ? "the caustics pass on the GPU (GLSL path)"
                                       : "the CPU photon reference (a periodic tile)"},
                    {"png", "caustics.png"},
                    {"tone_map", kCausticsToneMap}};
    if (c.pass) {
        j["texture"]["window"] = c.pass->window;
        j["pass"] = pass_json(*c.pass);
    }
    j["lit_bottom"] = {{"png", "bottom_lit.png"},
                       {"what", "the scene without the water surface, colour x mix(1, I, "
                                "caustics_strength) at each underwater pixel's bottom point "
                                "(the caustics node on the CPU, float)"}};
    return j;
}

std::optional<std::map<std::string, std::string>>
render_caustics_files(const RenderCaustics& c, float exposure, std::string* error) {
    std::map<std::string, std::string> files;
    const ImageRGBA8 texture = caustics_image(c.texture, c.texels);
    files["caustics.png"] = encode_png(texture.width, texture.height, texture.rgba, error);
    const ImageRGBA32F& b = c.lit_bottom;
    files["bottom_lit.png"] = encode_png(b.width, b.height, tone_map_to_srgb8(b, exposure), error);
    for (const auto& [name, bytes] : files)
        if (bytes.empty()) return std::nullopt;
    return files;
}

} // namespace watergen
