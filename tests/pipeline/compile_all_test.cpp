#include <catch2/catch.hpp>

#include "covering_builds.h"
#include "watergen/pipeline/variant/variant_build.h"

using namespace watergen;

// Every combination of the wired nodes: GLSL and HLSL compile with glslang, pass spirv-val
// (before and after spirv-opt), and the SPIRV-Cross GLSL 330 / ESSL 300 output compiles again.
TEST_CASE("every_wired_variant_compiles_validates_and_round_trips_in_both_languages", "[compile]") {
    for (const VariantBuild& b : test::covering_builds()) {
        INFO(b.shader.variant.key());
        for (const auto& d : b.diagnostics)
            INFO(format_diagnostic(d));
        REQUIRE(b.ok());
        for (const auto& lang : b.languages)
            for (const StageBuild* s : {&lang.vertex, &lang.fragment}) {
                INFO(s->source.file_name);
                CHECK(s->toolchain.ok());
                CHECK(s->toolchain.instruction_count > 0);
                CHECK(s->toolchain.instruction_count_optimized > 0);
                CHECK(s->toolchain.glsl330.find("#version 330") != std::string::npos);
                CHECK(s->toolchain.essl300.find("#version 300 es") != std::string::npos);
                CHECK(s->toolchain.msl.find("#include <metal_stdlib>") != std::string::npos);
            }
    }
}

TEST_CASE("glsl_and_hlsl_paths_share_one_descriptor_layout", "[compile]") {
    for (const VariantBuild& b : test::covering_builds()) {
        INFO(b.shader.variant.key());
        REQUIRE(b.ok());
        const auto& g = b.languages[0].fragment.toolchain.reflection.bindings;
        const auto& h = b.languages[1].fragment.toolchain.reflection.bindings;
        REQUIRE(g.size() == h.size());
        for (size_t i = 0; i < g.size(); ++i) {
            CHECK(g[i].name == h[i].name);
            CHECK(g[i].binding == h[i].binding);
            CHECK(g[i].kind == h[i].kind);
            CHECK(g[i].block_size == h[i].block_size);
            REQUIRE(g[i].members.size() == h[i].members.size());
            for (size_t m = 0; m < g[i].members.size(); ++m) {
                CHECK(g[i].members[m].name == h[i].members[m].name);
                CHECK(g[i].members[m].offset == h[i].members[m].offset);
            }
        }
    }
}

TEST_CASE("a_variant_declares_only_what_its_nodes_read", "[compile]") {
    Variant plain = default_variant();
    REQUIRE_FALSE(set_choice(plain, "extinction", "none"));
    REQUIRE_FALSE(set_choice(plain, "fresnel", "none"));
    const VariantBuild b = build_variant(plain);
    REQUIRE(b.ok());
    const std::string& glsl = b.languages[0].fragment.source.source;
    CHECK(glsl.find("absorb_coefficients") == std::string::npos);
    CHECK(glsl.find("ior_water") == std::string::npos);
    CHECK(glsl.find("fresnel_constant") != std::string::npos);
}
