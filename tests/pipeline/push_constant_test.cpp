// The parameter block as a push constant (a binding map's "kind": "push_constant"): both
// languages declare it with the uniform block's offsets, glslang and spirv-val accept both,
// the SPIR-V reflection has it as the stage's push-constant block and no descriptor, Metal and
// GL get it as a buffer and a uniform block, a block larger than the map's range is an error
// naming both sizes, and so is a block holding an array (bad map entries: binding_map_test.cpp).
#include <catch2/catch.hpp>

#include "watergen/ir/emit/emitter.h"
#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/plan/binding_map_file.h"
#include "watergen/plan/covering_array.h"
#include "watergen/water/binding_profiles.h"
#include "watergen/water/water_shader.h"

using namespace watergen;

namespace {

std::optional<BindingMap> parse_map(const std::string& text, Diagnostics& ds) {
    Diagnostic error;
    const auto src = JsonSource::parse(text, "map.json", &error);
    REQUIRE(src);
    return read_binding_map(*src, ds);
}

std::string messages(const Diagnostics& ds) {
    std::string s;
    for (const auto& d : ds)
        s += format_diagnostic(d) + "\n";
    return s;
}

// register_spaces with the block pushed: Metal buffer 3, GL uniform block binding 2.
BindingMap pushed_map(uint32_t bytes) {
    Diagnostics ds;
    auto map = parse_map(R"({"watergen_bindings": 1, "base": "register_spaces",
        "push_constant_bytes": )" +
                             std::to_string(bytes) + R"(,
        "resources": {"WaterParams": {"kind": "push_constant", "msl": 3, "gl": 2}}})",
                         ds);
    INFO(messages(ds));
    REQUIRE(map);
    return *map;
}

} // namespace

TEST_CASE("a_pushed_block_keeps_its_offsets_in_both_languages_and_every_target",
          "[bindings][push_constant]") {
    const BindingMap map = pushed_map(kMaxPushConstantBytes);
    const Variant v = default_variant();
    const VariantBuild pushed = build_variant(v, nullptr, EmitOptions{false, {}, {}, &map});
    INFO(messages(pushed.diagnostics));
    REQUIRE(pushed.ok()); // glslang (both front ends) and spirv-val accepted both modules
    const VariantBuild buffered = build_variant(v);
    REQUIRE(buffered.ok());

    const std::string& glsl = pushed.languages[0].fragment.source.source;
    const std::string& hlsl = pushed.languages[1].fragment.source.source;
    CHECK(glsl.find("layout(push_constant, std140) uniform WaterParams {") != std::string::npos);
    CHECK(hlsl.find("[[vk::push_constant]] cbuffer WaterParams {") != std::string::npos);
    CHECK(hlsl.find("register(b") == std::string::npos);

    const Reflection& want = buffered.languages[0].fragment.toolchain.reflection;
    const DescriptorBinding* block = nullptr;
    for (const DescriptorBinding& b : want.bindings)
        if (b.name == kParamsResource) block = &b;
    REQUIRE(block);
    for (const LanguageBuild& lang : pushed.languages) {
        INFO(to_string(lang.language));
        const Reflection& r = lang.fragment.toolchain.reflection;
        REQUIRE(r.push_constant);
        CHECK(r.push_constant->name == kParamsResource);
        CHECK(r.push_constant->kind == DescriptorKind::PushConstant);
        // The uniform buffer's layout, member by member: one packing for engines either way.
        CHECK(r.push_constant->block_size == block->block_size);
        REQUIRE(r.push_constant->members.size() == block->members.size());
        for (size_t i = 0; i < block->members.size(); ++i) {
            CHECK(r.push_constant->members[i].name == block->members[i].name);
            CHECK(r.push_constant->members[i].offset == block->members[i].offset);
        }
        for (const DescriptorBinding& b : r.bindings)
            CHECK(b.name != kParamsResource);
        CHECK(check_reflected_bindings(r, lang.fragment.source).empty());
    }
    // Metal: a buffer at the map's index; GL: a uniform block an engine binds at unit 2.
    const ToolchainOutputs& t = pushed.languages[0].fragment.toolchain;
    CHECK(t.msl.find("[[buffer(3)]]") != std::string::npos);
    CHECK(t.glsl330.find("uniform WaterParams") != std::string::npos);
    CHECK(t.essl300.find("uniform WaterParams") != std::string::npos);

    // The reflection check: a pushed block the map does not push is caught.
    Reflection stray = buffered.languages[0].fragment.toolchain.reflection;
    stray.push_constant = *block;
    stray.push_constant->kind = DescriptorKind::PushConstant;
    CHECK_FALSE(check_reflected_bindings(stray, buffered.languages[0].fragment.source).empty());
}

TEST_CASE("a_block_larger_than_the_push_range_is_an_error_naming_both_sizes",
          "[bindings][push_constant]") {
    // The covering variant with the largest block.
    Variant v;
    uint32_t size = 0;
    for (const Variant& c : pairwise_covering_variants()) {
        Diagnostics ds;
        const EmittedShader e =
            emit_fragment(build_water_shader(c).fragment, Language::Glsl, "f", "", ds);
        REQUIRE_FALSE(has_errors(ds));
        if (e.interface.uniforms.size > size) size = e.interface.uniforms.size, v = c;
    }
    INFO(v.key());
    CHECK(size == 752); // Gerstner's wave arrays (directions, speeds, phases): a register each

    const BindingMap small = pushed_map(kGuaranteedPushConstantBytes);
    const VariantBuild b = build_variant(v, nullptr, EmitOptions{false, {}, {}, &small});
    REQUIRE_FALSE(b.ok());
    const std::string says = messages(b.diagnostics);
    INFO(says);
    CHECK(says.find("the parameter block WaterParams is " + std::to_string(size) +
                    " bytes in this variant") != std::string::npos);
    CHECK(says.find("a push constant of at most 128 bytes") != std::string::npos);

    // Its arrays cannot be pushed at any size (the HLSL front end's strides would differ).
    const BindingMap roomy = pushed_map(kMaxPushConstantBytes);
    const VariantBuild arrays = build_variant(v, nullptr, EmitOptions{false, {}, {}, &roomy});
    CHECK_FALSE(arrays.ok());
    CHECK(messages(arrays.diagnostics).find("holds the array '") != std::string::npos);

    // A block without arrays fits at exactly its size: the default variant's 128 bytes, the
    // size every Vulkan device pushes (its position texture is camera-relative, so no frame
    // centre joins the block).
    Diagnostics ds;
    CHECK(emit_fragment(build_water_shader(default_variant()).fragment, Language::Glsl, "f", "", ds)
              .interface.uniforms.size == 128);
    CHECK(build_variant(default_variant(), nullptr, EmitOptions{false, {}, {}, &small}).ok());
    const BindingMap tight = pushed_map(112);
    CHECK_FALSE(build_variant(default_variant(), nullptr, EmitOptions{false, {}, {}, &tight}).ok());
}

TEST_CASE("a_pushed_map_reads_back_as_written", "[bindings][push_constant]") {
    const BindingMap map = pushed_map(256);
    const ResourceSlot* p = map.push_constant();
    REQUIRE(p);
    CHECK(p->name == kParamsResource);
    CHECK(std::tie(p->set, p->binding, p->hlsl_register, p->hlsl_space, p->msl_index, p->gl_unit) ==
          std::make_tuple(0u, 0u, 0u, 0u, 3u, 2u));
    const auto json = binding_map_json(map);
    CHECK(json["push_constant_bytes"] == 256);
    CHECK(json["resources"]["WaterParams"].dump() == R"({"kind":"push_constant","msl":3,"gl":2})");
    Diagnostics ds;
    const auto back = parse_map(json.dump(2), ds);
    INFO(messages(ds));
    REQUIRE(back);
    CHECK(back->push_constant_bytes == 256);
    REQUIRE(back->push_constant());
    CHECK(back->push_constant()->msl_index == 3);
    // A map without one writes no push_constant_bytes (files and manifests keep their form).
    CHECK_FALSE(binding_map_json(default_binding_map()).contains("push_constant_bytes"));
}

TEST_CASE("a_map_that_pushes_a_texture_is_an_error_naming_it", "[bindings][push_constant]") {
    // A texture the map pushes: the shader reads it as a texture.
    Diagnostics ds;
    const auto map = parse_map(R"({"watergen_bindings": 1, "base": "watergen",
        "resources": {"scene_color": {"kind": "push_constant", "msl": 9, "gl": 9}}})",
                               ds);
    REQUIRE(map);
    emit_fragment(build_water_shader(default_variant()).fragment, Language::Glsl, "f", "", ds,
                  EmitOptions{false, {}, {}, &*map});
    REQUIRE(has_errors(ds));
    CHECK(messages(ds).find("places 'scene_color'") != std::string::npos);
}
