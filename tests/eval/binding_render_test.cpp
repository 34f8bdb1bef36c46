// A binding map moves descriptors, never pixels: variants that together read every texture,
// drawn on lavapipe through both language paths under each profile and a map of high sets and
// spaces, equal the default map's images pixel by pixel (max abs 0). The runner binds by
// reflection, so the draw follows each map's sets and bindings.
#include <catch2/catch.hpp>

#include <set>

#include "shared_runner.h"
#include "watergen/eval/draw/variant_render.h"
#include "watergen/plan/binding_map_file.h"
#include "watergen/plan/covering_array.h"
#include "watergen/water/binding_profiles.h"
#include "watergen/water/water_shader.h"

using namespace watergen;

namespace {

// Covering variants, taken while they add a texture no earlier one reads.
std::vector<Variant> variants_reading_every_texture() {
    std::vector<Variant> picked;
    std::set<std::string> read;
    for (const Variant& v : pairwise_covering_variants()) {
        Diagnostics ds;
        const EmittedShader e =
            emit_fragment(build_water_shader(v).fragment, Language::Glsl, "f", "", ds);
        bool adds = false;
        for (const TextureBinding& t : e.interface.textures)
            adds |= read.insert(t.name).second;
        if (adds) picked.push_back(v);
    }
    REQUIRE(read.size() == 12);
    return picked;
}

float max_abs(const ImageRGBA32F& a, const ImageRGBA32F& b) {
    REQUIRE(a.rgba.size() == b.rgba.size());
    float worst = 0;
    for (size_t i = 0; i < a.rgba.size(); ++i)
        worst = std::max(worst, std::fabs(a.rgba[i] - b.rgba[i]));
    return worst;
}

} // namespace

TEST_CASE("every_binding_map_draws_the_default_maps_pixels", "[render][bindings]") {
    Diagnostics ds;
    const JsonSource src = *JsonSource::parse(R"({"watergen_bindings": 1,
        "base": "register_spaces",
        "resources": {"WaterParams": {"set": 3, "binding": 9, "hlsl_space": 3}}})",
                                              "high_sets.json", nullptr);
    const std::optional<BindingMap> high = read_binding_map(src, ds);
    REQUIRE(high);
    std::vector<const BindingMap*> maps = {high ? &*high : nullptr};
    for (const std::string& name : binding_profile_names())
        if (name != "watergen") maps.push_back(binding_profile(name));

    const RenderSettings settings{64, 64, 1, false, false};
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    const std::vector<Variant> variants = variants_reading_every_texture();
    REQUIRE(variants.size() >= 3);
    for (const Variant& v : variants) {
        INFO(v.key());
        const VariantBuild base = build_variant(v);
        REQUIRE(base.ok());
        const VariantRender want = render_variant(test::shared_runner(), base, scene, settings);
        INFO(want.error);
        REQUIRE(want.ok());
        for (const BindingMap* map : maps) {
            INFO(map->name);
            const VariantBuild b = build_variant(v, nullptr, EmitOptions{false, {}, {}, map});
            REQUIRE(b.ok());
            const VariantRender got = render_variant(test::shared_runner(), b, scene, settings);
            INFO(got.error);
            REQUIRE(got.ok());
            CHECK(got.validation_messages.empty());
            for (size_t path = 0; path < 2; ++path)
                CHECK(max_abs(got.gpu_image[path], want.gpu_image[path]) == 0.0f);
        }
    }
}

// The block as a push constant (128 bytes: what every Vulkan device pushes, lavapipe's limit):
// the runner pushes the bytes it would have put in the uniform buffer, and the images equal the
// uniform buffer's pixel by pixel, GLSL equals HLSL, and both agree with the CPU evaluation of
// the same graph within the float bound. Variants of the covering set whose block fits (no
// arrays, at most 128 bytes) and the default variant.
TEST_CASE("a_pushed_block_draws_the_uniform_buffers_pixels", "[render][bindings][push_constant]") {
    Diagnostics ds;
    const JsonSource src = *JsonSource::parse(R"({"watergen_bindings": 1, "base": "watergen",
        "resources": {"WaterParams": {"kind": "push_constant"}}})",
                                              "pushed.json", nullptr);
    const std::optional<BindingMap> pushed = read_binding_map(src, ds);
    REQUIRE(pushed);
    REQUIRE(pushed->push_constant_bytes == 128);

    RenderSettings settings{64, 64, 1, true, true};
    settings.float_bound = true;
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    std::vector<Variant> variants = {default_variant()};
    for (const Variant& v : pairwise_covering_variants())
        if (variants.size() < 4 && v.key() != default_variant().key() &&
            build_variant(v, nullptr, EmitOptions{false, {}, {}, &*pushed}).ok())
            variants.push_back(v);
    REQUIRE(variants.size() == 4);
    for (const Variant& v : variants) {
        INFO(v.key());
        const VariantBuild b = build_variant(v, nullptr, EmitOptions{false, {}, {}, &*pushed});
        REQUIRE(b.ok());
        REQUIRE(b.languages[0].fragment.toolchain.reflection.push_constant);
        const VariantRender got = render_variant(test::shared_runner(), b, scene, settings);
        INFO(got.error);
        REQUIRE(got.ok());
        CHECK(got.validation_messages.empty());
        const VariantRender want =
            render_variant(test::shared_runner(), build_variant(v), scene,
                           RenderSettings{settings.width, settings.height, 1, false, false});
        REQUIRE(want.ok());
        CHECK(max_abs(got.gpu_image[0], got.gpu_image[1]) == 0.0f);
        for (size_t path = 0; path < 2; ++path) {
            CHECK(max_abs(got.gpu_image[path], want.gpu_image[path]) == 0.0f);
            CHECK(got.agreement[path].over_bound == 0);
        }
    }
}
