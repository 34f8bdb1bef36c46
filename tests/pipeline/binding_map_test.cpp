// Binding maps: the profiles place every resource of every built-in choice without a clash, a
// build emits each at its slot in every target (GLSL and HLSL source, SPIR-V reflection, Metal),
// the slots do not move between variants, and a bad map file is an error at its line.
#include <catch2/catch.hpp>

#include <algorithm>
#include <set>

#include "watergen/ir/emit/emitter.h"
#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/plan/binding_map_file.h"
#include "watergen/plan/covering_array.h"
#include "watergen/water/binding_profiles.h"
#include "watergen/water/water_shader.h"

using namespace watergen;

namespace {

std::string messages(const Diagnostics& ds) {
    std::string s;
    for (const auto& d : ds)
        s += format_diagnostic(d) + "\n";
    return s;
}

std::optional<BindingMap> parse_map(const std::string& text, Diagnostics& ds) {
    Diagnostic error;
    const auto src = JsonSource::parse(text, "map.json", &error);
    REQUIRE(src);
    return read_binding_map(*src, ds);
}

// The variant of the covering set that reads the most textures.
Variant most_textured() {
    Variant best;
    size_t most = 0;
    for (const Variant& v : pairwise_covering_variants()) {
        Diagnostics ds;
        const size_t n = emit_fragment(build_water_shader(v).fragment, Language::Glsl, "f", "", ds)
                             .interface.textures.size();
        if (n > most) most = n, best = v;
    }
    return best;
}

} // namespace

TEST_CASE("every_profile_places_every_resource_of_every_choice_without_a_clash", "[bindings]") {
    for (const std::string& name : binding_profile_names()) {
        INFO(name);
        const BindingMap& map = *binding_profile(name);
        CHECK_FALSE(map.conflict());
        // The covering set holds every choice of every axis at least once.
        std::set<std::string> read;
        for (const Variant& v : pairwise_covering_variants())
            for (Language lang : {Language::Glsl, Language::Hlsl}) {
                Diagnostics ds;
                const EmittedShader e = emit_fragment(build_water_shader(v).fragment, lang, "f", "",
                                                      ds, EmitOptions{false, {}, {}, &map});
                INFO(v.key() << "\n" << messages(ds));
                REQUIRE_FALSE(has_errors(ds));
                // Each declared resource at the map's slot, whatever else the variant reads.
                for (const ResourceSlot& s : e.interface.slots) {
                    const ResourceSlot* want = map.find(s.name);
                    REQUIRE(want);
                    CHECK(s.set == want->set);
                    CHECK(s.binding == want->binding);
                    read.insert(s.name);
                }
            }
        // All eleven textures, the block and the sampler are read by some choice: no dead slot.
        CHECK(read.size() == map.slots.size());
    }
}

TEST_CASE("a_build_binds_each_resource_where_the_map_says_in_every_target", "[bindings]") {
    const BindingMap& map = *binding_profile("register_spaces");
    const Variant v = most_textured();
    const VariantBuild b = build_variant(v, nullptr, EmitOptions{false, {}, {}, &map});
    INFO(v.key() << "\n" << messages(b.diagnostics));
    REQUIRE(b.ok());
    const ShaderInterface& in = b.languages[0].fragment.source.interface;
    REQUIRE(in.textures.size() >= 4);
    for (const LanguageBuild& lang : b.languages) {
        const StageBuild& f = lang.fragment;
        // The reflection of the SPIR-V glslang made from the source: every slot, none else.
        REQUIRE(f.toolchain.reflection.bindings.size() == in.slots.size());
        for (const DescriptorBinding& d : f.toolchain.reflection.bindings) {
            INFO(d.name);
            const ResourceSlot* s = map.find(d.name);
            REQUIRE(s);
            CHECK(d.set == s->set);
            CHECK(d.binding == s->binding);
        }
        CHECK(check_reflected_bindings(f.toolchain.reflection, f.source).empty());
    }
    // Golden slots of the profile: the block b0 in space0, the per-view textures t0.. in
    // space1 (Vulkan set 1, binding 16 + register), the material's in space2.
    const std::string& hlsl = b.languages[1].fragment.source.source;
    CHECK(hlsl.find("[[vk::binding(0, 0)]] cbuffer WaterParams : register(b0, space0)") !=
          std::string::npos);
    CHECK(hlsl.find("[[vk::binding(32, 0)]] SamplerState linear_clamp : register(s0, space0);") !=
          std::string::npos);
    CHECK(hlsl.find("[[vk::binding(16, 1)]] Texture2D scene_color : register(t0, space1);") !=
          std::string::npos);
    const std::string& glsl = b.languages[0].fragment.source.source;
    CHECK(glsl.find("layout(set = 1, binding = 17) uniform texture2D scene_position;") !=
          std::string::npos);
    // Metal: each texture at the map's index, which SPIRV-Cross writes.
    const std::string& msl = b.languages[0].fragment.toolchain.msl;
    for (const TextureBinding& t : in.textures) {
        const ResourceSlot* s = map.find(t.name);
        INFO(t.name);
        CHECK(msl.find(t.name + " [[texture(" + std::to_string(s->msl_index) + ")]]") !=
              std::string::npos);
    }
}

TEST_CASE("a_resource_keeps_its_slot_in_every_variant", "[bindings]") {
    // Two variants that read different textures: the ones both read sit at one slot, and a
    // texture one of them skips does not move the others (dense numbering would).
    const BindingMap& map = default_binding_map();
    std::map<std::string, std::set<std::pair<uint32_t, uint32_t>>> seen;
    for (const Variant& v : pairwise_covering_variants()) {
        Diagnostics ds;
        const EmittedShader e = emit_fragment(build_water_shader(v).fragment, Language::Glsl, "f",
                                              "", ds, EmitOptions{false, {}, {}, &map});
        REQUIRE_FALSE(has_errors(ds));
        for (const TextureBinding& t : e.interface.textures)
            seen[t.name].insert({t.set, t.binding});
    }
    REQUIRE(seen.size() >= 8);
    for (const auto& [name, places] : seen) {
        INFO(name);
        CHECK(places.size() == 1);
    }
}

TEST_CASE("a_texture_the_map_does_not_place_is_an_error_naming_it", "[bindings]") {
    BindingMap map = default_binding_map();
    map.name = "engine.json";
    map.slots.erase(std::remove_if(map.slots.begin(), map.slots.end(),
                                   [](const ResourceSlot& s) { return s.name == "scene_color"; }),
                    map.slots.end());
    Diagnostics ds;
    emit_fragment(build_water_shader(pairwise_covering_variants().front()).fragment, Language::Hlsl,
                  "f", "", ds, EmitOptions{false, {}, {}, &map});
    REQUIRE(has_errors(ds));
    CHECK(ds.front().file == "engine.json");
    CHECK(ds.front().message.find("texture 'scene_color'") != std::string::npos);
    CHECK(ds.front().message.find("has no slot in the binding map engine.json") !=
          std::string::npos);
}

TEST_CASE("the_reflection_check_catches_a_resource_off_its_slot", "[bindings]") {
    const VariantBuild b = build_variant(pairwise_covering_variants().front());
    REQUIRE(b.ok());
    const StageBuild& f = b.languages[0].fragment;
    Reflection moved = f.toolchain.reflection;
    REQUIRE_FALSE(moved.bindings.empty());
    moved.bindings.back().binding += 40;
    const Diagnostics ds = check_reflected_bindings(moved, f.source);
    REQUIRE(ds.size() == 1);
    CHECK(ds[0].message.find("'" + moved.bindings.back().name + "' is at set 0 binding ") !=
          std::string::npos);
    Reflection missing = f.toolchain.reflection;
    missing.bindings.pop_back();
    CHECK(check_reflected_bindings(missing, f.source).size() == 1);
}

TEST_CASE("a_map_file_reads_back_as_written_and_overrides_its_base", "[bindings]") {
    for (const std::string& name : binding_profile_names()) {
        INFO(name);
        Diagnostics ds;
        const auto back = parse_map(binding_map_json(*binding_profile(name)).dump(2), ds);
        INFO(messages(ds));
        REQUIRE(back);
        REQUIRE(back->slots.size() == binding_profile(name)->slots.size());
        for (size_t i = 0; i < back->slots.size(); ++i) {
            const ResourceSlot &a = back->slots[i], &b = binding_profile(name)->slots[i];
            CHECK(std::tie(a.name, a.kind, a.set, a.binding, a.hlsl_register, a.hlsl_space,
                           a.msl_index, a.gl_unit) == std::tie(b.name, b.kind, b.set, b.binding,
                                                               b.hlsl_register, b.hlsl_space,
                                                               b.msl_index, b.gl_unit));
        }
    }
    Diagnostics ds;
    const auto m = parse_map(R"({"watergen_bindings": 1, "base": "watergen",
        "resources": {"WaterParams": {"set": 3, "binding": 5, "hlsl_space": 3}}})",
                             ds);
    INFO(messages(ds));
    REQUIRE(m);
    const ResourceSlot* p = m->find("WaterParams");
    REQUIRE(p);
    CHECK(p->set == 3);
    CHECK(p->binding == 5);
    CHECK(p->hlsl_space == 3);
    CHECK(p->hlsl_register == 0); // kept from the base
    CHECK(p->origin.rfind("map.json:2:", 0) == 0);
    CHECK(m->slots.size() == binding_profile("watergen")->slots.size());
    // Without a base every resource is new: its register and space default to its binding and
    // set, its kind to the name's.
    Diagnostics fresh_ds;
    const auto fresh = parse_map(R"({"watergen_bindings": 1,
        "resources": {"scene_color": {"set": 1, "binding": 0, "msl": 20, "gl": 20}}})",
                                 fresh_ds);
    INFO(messages(fresh_ds));
    REQUIRE(fresh);
    const ResourceSlot* colour = fresh->find("scene_color");
    REQUIRE(colour);
    CHECK(colour->kind == ResourceKind::Texture);
    CHECK(std::tie(colour->hlsl_register, colour->hlsl_space, colour->msl_index, colour->gl_unit) ==
          std::make_tuple(0u, 1u, 20u, 20u));
    CHECK(fresh->slots.size() == 1);
}

TEST_CASE("a_bad_map_file_is_an_error_at_its_line", "[bindings]") {
    struct Case {
        const char* text;
        int line;
        const char* says;
    };
    const Case cases[] = {
        // A clash names both resources and both lines; the error sits at the later one.
        {"{\"watergen_bindings\": 1, \"resources\": {\n"
         "  \"WaterParams\": {\"set\": 0, \"binding\": 0},\n"
         "  \"scene_color\": {\"set\": 0, \"binding\": 0}}}",
         3,
         "resources 'WaterParams' (map.json:2:3) and 'scene_color' (map.json:3:3) are both at "
         "Vulkan set 0 binding 0"},
        {"{\"watergen_bindings\": 1, \"resources\": {\n"
         "  \"scene_color\": {\"set\": 0, \"binding\": 1, \"msl\": 4},\n"
         "  \"sky_cube\": {\"set\": 0, \"binding\": 2, \"msl\": 4}}}",
         3, "are both at Metal [[texture(4)]]"},
        {"{\"watergen_bindings\": 1, \"resources\": {\n  \"a\": {\"set\": -1, \"binding\": 0}}}", 2,
         "/resources/a/set: expected a whole number from 0 to 3 (Vulkan guarantees 4 bound "
         "descriptor sets), got -1"},
        {"{\"watergen_bindings\": 1, \"resources\": {\n  \"a\": {\"set\": 0, \"binding\": 5000}}}",
         2, "/resources/a/binding: expected a whole number from 0 to 4095, got 5000"},
        {"{\"watergen_bindings\": 1, \"resources\": {\n  \"a\": {\"binding\": 0}}}", 2,
         "needs \"set\" and \"binding\""},
        {"{\"watergen_bindings\": 1, \"resources\": {\n  \"a\": {\"set\": 0, \"binding\": 0, "
         "\"register\": 1}}}",
         2, "register"},
        {"{\"watergen_bindings\": 1,\n \"base\": \"unreal\", \"resources\": {}}", 2, "/base"},
        {"{\"watergen_bindings\": 2, \"resources\": {}}", 1, "expected 1"},
        {"{\"watergen_bindings\": 1, \"resources\": {\n  \"9lives\": {\"set\": 0, \"binding\": "
         "0}}}",
         2, "not a shader identifier"},
        // A name no shader reads (a misspelling): refused at its line with the name it meant.
        {"{\"watergen_bindings\": 1, \"base\": \"watergen\", \"resources\": {\n"
         "  \"scene_colour\": {\"set\": 0, \"binding\": 20}}}",
         2,
         "'scene_colour' is not a resource any shader of this generator reads (did you mean "
         "'scene_color'?)"},
        // Push constants (push_constant_test.cpp): no set, binding or register; a range in
        // whole registers and at most 4096 bytes; one block.
        {"{\"watergen_bindings\": 1, \"base\": \"watergen\", \"resources\": {\n"
         "  \"WaterParams\": {\"kind\": \"push_constant\", \"set\": 1}}}",
         2, "a push constant has no descriptor set, binding or HLSL register"},
        {"{\"watergen_bindings\": 1, \"base\": \"watergen\",\n \"push_constant_bytes\": 100,\n"
         " \"resources\": {\"WaterParams\": {\"kind\": \"push_constant\"}}}",
         2, "expected a multiple of 16 bytes"},
        {"{\"watergen_bindings\": 1, \"base\": \"watergen\",\n \"push_constant_bytes\": 8192,\n"
         " \"resources\": {\"WaterParams\": {\"kind\": \"push_constant\"}}}",
         2, "expected a whole number from 0 to 4096"},
        {"{\"watergen_bindings\": 1, \"base\": \"watergen\", \"resources\": {\n"
         "  \"WaterParams\": {\"kind\": \"push_constant\"},\n"
         "  \"linear_clamp\": {\"kind\": \"push_constant\", \"msl\": 9, \"gl\": 9}}}",
         3, "are both push constants"},
    };
    for (const Case& c : cases) {
        INFO(c.text);
        Diagnostics ds;
        CHECK_FALSE(parse_map(c.text, ds));
        REQUIRE(ds.size() == 1);
        INFO(format_diagnostic(ds[0]));
        CHECK(ds[0].file == "map.json");
        CHECK(ds[0].line == c.line);
        CHECK(ds[0].message.find(c.says) != std::string::npos);
    }
    Diagnostics ds;
    CHECK_FALSE(load_binding_map("engine_layout", ds));
    REQUIRE(ds.size() == 1);
    CHECK(ds[0].message.find("not a profile either; the profiles are watergen, frequency_sets, "
                             "register_spaces") != std::string::npos);
}
