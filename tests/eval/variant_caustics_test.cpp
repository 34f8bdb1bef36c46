// `watergen render` of caustics variants (draw/variant_caustics.h): the pass drawn for the
// scene becomes the map the water pass and the CPU evaluator sample, the files beside the render,
// and caustics=none untouched. Figures measured on lavapipe are in comments.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <set>

#include "compare_report_support.h"
#include "shared_runner.h"
#include "watergen/eval/draw/variant_caustics.h"
#include "watergen/eval/report/render_report.h"

using namespace watergen;
using namespace watergen::test;
namespace fs = std::filesystem;

namespace {

Variant caustics_variant(const std::string& caustics, const std::string& waves) {
    Variant v = default_variant();
    REQUIRE_FALSE(set_choice(v, "caustics", caustics));
    REQUIRE_FALSE(set_choice(v, "waves", waves));
    return v;
}

struct Rendered {
    RenderCaustics caustics;
    VariantRender render;
    SyntheticScene scene;
    fs::path dir;
};

// What the render command does: the caustics (if any) for the scene, the render over it, the
// files written into a scratch directory.
Rendered render_with_caustics(const Variant& v, const std::string& name) {
    const VariantBuild build = build_variant(v, nullptr);
    REQUIRE(build.ok());
    Rendered out;
    out.scene = make_synthetic_scene(256, 256);
    RenderExtras extras;
    if (has_caustics(v)) {
        out.caustics = prepare_render_caustics(shared_runner(), v, build, out.scene, 3);
        INFO(out.caustics.error);
        REQUIRE(out.caustics.ok());
        std::string error;
        const auto files = render_caustics_files(out.caustics, 1.0f, &error);
        INFO(error);
        REQUIRE(files);
        extras.files = *files;
        extras.json["caustics"] = render_caustics_json(out.caustics);
    }
    out.render = render_variant(shared_runner(), build, out.scene, {256, 256, 1, false, true});
    INFO(out.render.error);
    REQUIRE(out.render.ok());
    out.dir = fs::current_path() / ("scratch-render-caustics-" + name);
    const RenderReportInfo info{"", "off", shared_runner().device_info(), 256, 256, 1.0, "beach"};
    REQUIRE_FALSE(write_render_report(out.dir, out.render, info, extras));
    return out;
}

std::set<std::string> files_in(const fs::path& dir) {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir))
        names.insert(entry.path().filename().string());
    return names;
}

} // namespace

// The beach view's area-ratio pass over the scene's Gerstner waves, 64x64, 2 m deep, against the
// photon reference (64 per texel): measured RMSE 0.0098, max abs 0.245 at texel (29, 25), mean
// 0.99069 against 0.99052. The grid and the photons cover the window grown by caustics_margin()
// (3.4 m); with 1 m (before) the light a low sun carries in from outside was lost differently
// at the edge: RMSE 0.0238, max abs 0.477 at texel (32, 0). The max abs is now inside, at the
// sharpest caustic, where a fragment's area ratio differs from the photons' texel average.
// Bounds: RMSE 0.015 and max abs 0.37 (about 1.5x).
TEST_CASE("render_of_an_area_ratio_variant_samples_the_pass_it_drew", "[render][caustics]") {
    const Rendered r = render_with_caustics(caustics_variant("area_ratio", "gerstner"), "area");
    REQUIRE(r.caustics.pass);
    const SceneCausticsPass& p = *r.caustics.pass;
    CHECK(p.method == CausticsMethod::AreaRatio);
    CHECK(p.wave_model == "gerstner");
    CHECK(p.texels == 64);
    CHECK(p.glsl_vs_hlsl == 0); // the two languages draw the same texture
    CHECK(p.glsl.steady_draw_ms > 0);
    const auto worst =
        std::max_element(p.intensity.begin(), p.intensity.end(),
                         [&](const double& a, const double& b) {
                             const size_t i = &a - p.intensity.data();
                             const size_t j = &b - p.intensity.data();
                             return std::abs(a - p.reference[i]) < std::abs(b - p.reference[j]);
                         }) -
        p.intensity.begin();
    WARN("area_ratio vs reference: RMSE "
         << p.vs_reference.rmse << ", max abs " << p.vs_reference.max_abs << " at texel ("
         << worst % 64 << ", " << worst / 64 << "), mean " << p.mean << " vs " << p.reference_mean);
    CHECK(p.vs_reference.rmse < 0.015);
    CHECK(p.vs_reference.max_abs < 0.37);
    CHECK(p.mean == Approx(p.reference_mean).margin(0.005));
    // The scene carries the GPU texture: the water pass and the CPU evaluator sampled it.
    const TextureData& map = r.scene.textures.at("caustics_map");
    REQUIRE(map.rgba.size() == p.intensity.size() * 4);
    for (size_t i = 0; i < p.intensity.size(); ++i)
        REQUIRE(map.rgba[i * 4] == float(p.intensity[i]));
    // And they agree as tightly as every variant does (measured 5.66e-07).
    CHECK(r.render.glsl_vs_hlsl.max_abs == 0);
    CHECK(r.render.glsl_vs_cpu_float.max_abs <= 5e-5);
    CHECK(r.render.hlsl_vs_cpu_float.max_abs <= 5e-5);
    // The files: the texture at its size, the lit bottom at the render's.
    std::string why;
    const auto texture = decode_png(read_file_text(r.dir / "caustics.png"), &why);
    const auto bottom = decode_png(read_file_text(r.dir / "bottom_lit.png"), &why);
    INFO(why);
    REQUIRE(texture);
    REQUIRE(bottom);
    CHECK(texture->width == 64);
    CHECK(bottom->width == 256);
    CHECK(bottom->height == 256);
    const std::string json = read_file_text(r.dir / "render.json");
    CHECK(json.find("\"vs_reference\"") != std::string::npos);
    fs::remove_all(r.dir);
}

// The lit bottom is the scene's colour times mix(1, I, caustics_strength): 1 above the water,
// brighter and darker than the scene where the map focuses and spreads light.
TEST_CASE("the_lit_bottom_scales_underwater_pixels_by_the_caustics", "[render][caustics]") {
    const Rendered r = render_with_caustics(caustics_variant("area_ratio", "gerstner"), "bottom");
    const TextureData& color = r.scene.textures.at("scene_color");
    const TextureData& position = r.scene.textures.at("scene_position");
    const ImageRGBA32F& lit = r.caustics.lit_bottom;
    REQUIRE(lit.rgba.size() == color.rgba.size());
    size_t brighter = 0, darker = 0;
    for (size_t p = 0; p < size_t(256) * 256; ++p) {
        const double ratio = lit.rgba[p * 4 + 1] / color.rgba[p * 4 + 1];
        // The texel is the point less the eye: above the water (y >= 0) it stays unlit.
        if (r.scene.position_eye[1] + position.rgba[p * 4 + 1] >= 0)
            REQUIRE(lit.rgba[p * 4 + 1] == color.rgba[p * 4 + 1]);
        brighter += ratio > 1.05;
        darker += ratio < 0.95;
    }
    CHECK(brighter > 500);
    CHECK(darker > 500);
    fs::remove_all(r.dir);
}

// caustics=none: no pass, no extra file, render.json without a caustics block.
TEST_CASE("render_without_caustics_writes_what_it_wrote_before", "[render][caustics]") {
    const Variant v = default_variant();
    REQUIRE_FALSE(has_caustics(v));
    const Rendered r = render_with_caustics(v, "none");
    CHECK(files_in(r.dir) == std::set<std::string>{"glsl.png", "hlsl.png", "glsl.pfm", "hlsl.pfm",
                                                   "cpu_float.pfm", "render.json"});
    CHECK(read_file_text(r.dir / "render.json").find("\"caustics\":") == std::string::npos);
    CHECK(r.scene.textures.at("caustics_map").rgba ==
          make_synthetic_scene(256, 256).textures.at("caustics_map").rgba);
    fs::remove_all(r.dir);
}
