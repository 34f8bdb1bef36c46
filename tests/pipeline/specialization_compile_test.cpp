// Specialization constants (EmitOptions::specialization_constants): a variant with parameters
// baked at pipeline creation passes the whole toolchain in both languages, keeps one descriptor
// layout, and reflects every constant with its id, default and range.
#include <catch2/catch.hpp>

#include <algorithm>
#include <set>
#include <string>

#include "specialization_support.h"
#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/toolchain/reflection_stage.h"
#include "watergen/water/presets.h"

using namespace watergen;

namespace {

// The float parameters the variant's fragment stage reads, in declaration order.
std::vector<Parameter> read_parameters(const Preset* preset,
                                       const Variant& variant = default_variant()) {
    const VariantBuild plain = build_variant(variant, preset);
    REQUIRE(plain.ok());
    return plain.languages[0].fragment.source.interface.parameters;
}

std::string diagnostics_text(const Diagnostics& ds) {
    std::string text;
    for (const auto& d : ds)
        text += format_diagnostic(d) + "\n";
    return text;
}

// What the reflection of `parameters` as specialization constants must list: one float per
// component, ids counted in declaration order, "_x".."_w" for vector components.
std::vector<SpecializationConstant> expected_constants(const std::vector<Parameter>& parameters,
                                                       const std::set<std::string>& names) {
    std::vector<SpecializationConstant> out;
    for (const auto& p : parameters) {
        if (!names.count(p.name)) continue;
        const size_t n = p.default_value.size();
        for (size_t c = 0; c < n; ++c)
            out.push_back({static_cast<uint32_t>(out.size()),
                           n == 1 ? p.name : p.name + "_" + "xyzw"[c], "float",
                           static_cast<float>(p.default_value[c]), p.min, p.max});
    }
    return out;
}

// `got` lists constants of `want` (each with its id, default and range), in id order; all of
// them unless the module had some removed as dead code (see below).
void check_constants(const std::vector<SpecializationConstant>& got,
                     const std::vector<SpecializationConstant>& want, bool all = true) {
    std::string names;
    for (const auto& c : got)
        names += c.name + " ";
    INFO(names);
    if (all) REQUIRE(got.size() == want.size());
    REQUIRE(got.size() <= want.size());
    for (size_t i = 0; i < got.size(); ++i) {
        if (i > 0) CHECK(got[i - 1].id < got[i].id);
        REQUIRE(got[i].id < want.size());
        const SpecializationConstant& w = want[got[i].id];
        INFO(w.name);
        CHECK(got[i].name == w.name);
        CHECK(got[i].type == "float");
        CHECK(got[i].default_value == w.default_value);
        CHECK(got[i].min == w.min);
        CHECK(got[i].max == w.max);
    }
}

std::set<std::string> names_of(const std::vector<SpecializationConstant>& constants) {
    std::set<std::string> names;
    for (const auto& c : constants)
        names.insert(c.name);
    return names;
}

bool includes(const std::set<std::string>& a, const std::set<std::string>& b) {
    return std::includes(a.begin(), a.end(), b.begin(), b.end());
}

const DescriptorBinding* uniform_block(const Reflection& r) {
    for (const auto& b : r.bindings)
        if (b.kind == DescriptorKind::UniformBuffer) return &b;
    return nullptr;
}

} // namespace

TEST_CASE("specialized_parameters_compile_and_reflect_in_both_languages", "[compile]") {
    const Preset* preset = find_preset("tropical_ocean");
    REQUIRE(preset != nullptr);
    const std::vector<Parameter> parameters = read_parameters(preset);
    // Every other read parameter, a vec3 and a float among them, so the block keeps some.
    std::set<std::string> names;
    bool vector = false, scalar = false;
    for (size_t i = 0; i < parameters.size(); i += 2) {
        names.insert(parameters[i].name);
        vector = vector || parameters[i].type == Type::Vec3;
        scalar = scalar || parameters[i].type == Type::Float;
    }
    REQUIRE(vector);
    REQUIRE(scalar);
    REQUIRE(names.count("sun_direction")); // a preset value: the default is the preset's

    const VariantBuild b = build_variant(default_variant(), preset, EmitOptions{false, names});
    INFO(diagnostics_text(b.diagnostics));
    REQUIRE(b.ok());
    const std::vector<SpecializationConstant> want = expected_constants(parameters, names);
    // glslang's GLSL front end keeps every declared constant; the HLSL path (legalisation) and
    // spirv-opt drop dead code, here the refraction distortion a flat normal multiplies by 0.
    // What one drops the other cannot need: optimised GLSL <= HLSL <= declared.
    std::set<std::string> optimized_glsl;
    for (const auto& lang : b.languages) {
        INFO(to_string(lang.language));
        const ToolchainOutputs& t = lang.fragment.toolchain;
        REQUIRE(t.ok()); // glslang, spirv-val, spirv-opt, spirv-val, SPIRV-Cross, round trip
        const bool glsl = lang.language == Language::Glsl;
        check_constants(t.reflection.specialization_constants, want, glsl);
        // spirv-opt keeps them specializable (nothing froze them to their defaults).
        ReflectResult optimized = reflect_spirv(t.spirv_optimized, ShaderStage::Fragment);
        REQUIRE(optimized.diagnostics.empty());
        add_specialization_ranges(optimized.reflection,
                                  lang.fragment.source.interface.specialization);
        check_constants(optimized.reflection.specialization_constants, want, false);
        if (glsl)
            optimized_glsl = names_of(optimized.reflection.specialization_constants);
        else
            CHECK(includes(names_of(t.reflection.specialization_constants), optimized_glsl));
        CHECK(optimized.reflection.specialization_constants.size() + 2 >= want.size());
        // The block holds exactly the parameters that are not constants.
        const DescriptorBinding* block = uniform_block(t.reflection);
        REQUIRE(block != nullptr);
        std::set<std::string> members;
        for (const auto& m : block->members)
            members.insert(m.name);
        for (const auto& p : parameters)
            CHECK(members.count(p.name) == (names.count(p.name) ? 0u : 1u));
        CHECK(t.glsl330.find("SPIRV_CROSS_CONSTANT_ID_0") != std::string::npos);
        CHECK(t.msl.find("[[function_constant(0)]]") != std::string::npos);
    }
    // One descriptor layout for both languages, as without constants.
    const Reflection& glsl = b.languages[0].fragment.toolchain.reflection;
    const Reflection& hlsl = b.languages[1].fragment.toolchain.reflection;
    REQUIRE(glsl.bindings.size() == hlsl.bindings.size());
    for (size_t i = 0; i < glsl.bindings.size(); ++i) {
        CHECK(glsl.bindings[i].binding == hlsl.bindings[i].binding);
        CHECK(glsl.bindings[i].kind == hlsl.bindings[i].kind);
        CHECK(glsl.bindings[i].block_size == hlsl.bindings[i].block_size);
        REQUIRE(glsl.bindings[i].members.size() == hlsl.bindings[i].members.size());
        for (size_t m = 0; m < glsl.bindings[i].members.size(); ++m) {
            CHECK(glsl.bindings[i].members[m].name == hlsl.bindings[i].members[m].name);
            CHECK(glsl.bindings[i].members[m].offset == hlsl.bindings[i].members[m].offset);
        }
    }
    // The files say the same: reflection JSON (deterministic) and variant.json.
    const auto files = variant_files(b);
    const auto again =
        variant_files(build_variant(default_variant(), preset, EmitOptions{false, names}));
    CHECK(files == again);
    CHECK(files.at("glsl/water.frag.reflect.json").find("\"specialization_constants\"") !=
          std::string::npos);
    CHECK(files.at("variant.json").find("\"constant_ids\"") != std::string::npos);
}

TEST_CASE("every_float_parameter_can_be_a_specialization_constant", "[compile]") {
    // The default variant, and one whose surface search reads parameters inside loops.
    Variant marching = default_variant();
    REQUIRE_FALSE(set_choice(marching, "waves", "heightmap_march_converged"));
    for (const Variant& v : {default_variant(), marching}) {
        INFO(v.key());
        const std::vector<Parameter> parameters = read_parameters(nullptr, v);
        std::set<std::string> names;
        for (const auto& p : parameters)
            names.insert(p.name);
        const VariantBuild b = build_variant(v, nullptr, EmitOptions{false, names});
        INFO(diagnostics_text(b.diagnostics));
        REQUIRE(b.ok());
        for (const auto& lang : b.languages) {
            const Reflection& r = lang.fragment.toolchain.reflection;
            CHECK(uniform_block(r) == nullptr); // nothing left in the block: no binding 0
            check_constants(r.specialization_constants, expected_constants(parameters, names),
                            lang.language == Language::Glsl);
            CHECK(lang.fragment.source.source.find("params.") == std::string::npos);
            const bool loops = lang.fragment.source.source.find(" for (int ") != std::string::npos;
            CHECK(loops == (v.choice("waves") == "heightmap_march_converged"));
        }
    }
}

TEST_CASE("a_specialization_constant_naming_no_parameter_is_an_error", "[compile]") {
    const VariantBuild b =
        build_variant(default_variant(), nullptr, EmitOptions{false, {"sun_directoin"}});
    CHECK_FALSE(b.ok());
    CHECK(diagnostics_text(b.diagnostics)
              .find("specialization constant 'sun_directoin' names no parameter") !=
          std::string::npos);
}

TEST_CASE("a_parameter_marked_specialization_compiles_as_constants_in_both_languages",
          "[compile]") {
    const Graph g = test::tint_graph();
    for (Language lang : {Language::Glsl, Language::Hlsl}) {
        INFO(to_string(lang));
        Diagnostics ds;
        const EmittedShader s = emit_fragment(g, lang, "t.frag", "test", ds);
        REQUIRE(ds.empty());
        CompileRequest request{lang == Language::Glsl ? SourceLanguage::Glsl : SourceLanguage::Hlsl,
                               ShaderStage::Fragment, s.source, s.file_name, "main"};
        ToolchainOutputs t = run_toolchain(request);
        INFO(diagnostics_text(t.diagnostics));
        REQUIRE(t.ok());
        add_specialization_ranges(t.reflection, s.interface.specialization);
        Parameter tint = test::tint_parameter();
        check_constants(t.reflection.specialization_constants,
                        expected_constants({tint}, {"tint"}));
        const DescriptorBinding* block = uniform_block(t.reflection);
        REQUIRE(block != nullptr);
        REQUIRE(block->members.size() == 1);
        CHECK(block->members[0].name == "gain");
    }
}
