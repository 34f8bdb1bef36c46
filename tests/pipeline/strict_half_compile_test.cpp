// Strict half (EmitOptions::strict_half): every half variant of the covering set is written in
// explicit 16-bit types and still passes the whole toolchain in both languages.
#include <catch2/catch.hpp>

#include <string>

#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/plan/covering_array.h"
#include "watergen/toolchain/spirv_tools_stage.h"

using namespace watergen;

namespace {

size_t count(const std::string& text, const std::string& word) {
    size_t n = 0;
    for (size_t p = text.find(word); p != std::string::npos; p = text.find(word, p + 1))
        ++n;
    return n;
}

} // namespace

TEST_CASE("strict_half_variants_compile_in_16_bit_types_in_both_languages", "[compile]") {
    size_t half_variants = 0;
    for (const Variant& v : pairwise_covering_variants()) {
        if (v.choice("precision") != "half") continue;
        ++half_variants;
        INFO(v.key());
        const VariantBuild b = build_variant(v, nullptr, EmitOptions{true});
        std::string diagnostics;
        for (const auto& d : b.diagnostics)
            diagnostics += format_diagnostic(d) + "\n";
        INFO(diagnostics);
        REQUIRE(b.ok());
        const std::string& glsl = b.languages[0].fragment.source.source;
        const std::string& hlsl = b.languages[1].fragment.source.source;
        CHECK(glsl.find("GL_EXT_shader_explicit_arithmetic_types_float16") != std::string::npos);
        CHECK(count(glsl, "mediump") == 0);
        CHECK(count(hlsl, "min16float") == 0);
        // The shading math is in 16-bit types: temporaries and conversions in both languages.
        CHECK(count(glsl, "float16_t") + count(glsl, "f16vec") > 10);
        CHECK(count(hlsl, "half") > 10);
        for (const auto& lang : b.languages) {
            const ToolchainOutputs& t = lang.fragment.toolchain;
            CHECK(t.ok());
            // The module computes in binary16, not in relaxed 32-bit floats.
            CHECK(declares_capability(t.spirv, kCapabilityFloat16));
            CHECK(declares_capability(t.spirv_optimized, kCapabilityFloat16));
            CHECK(t.msl.find(" half") != std::string::npos);
            CHECK(t.glsl330.empty()); // no 16-bit float type in GLSL 330 / ESSL 300: skipped
        }
    }
    CHECK(half_variants > 0);
}

TEST_CASE("strict_half_leaves_a_full_precision_variant_unchanged", "[compile]") {
    Variant v = default_variant();
    REQUIRE_FALSE(set_choice(v, "precision", "full"));
    const VariantBuild plain = build_variant(v);
    const VariantBuild strict = build_variant(v, nullptr, EmitOptions{true});
    REQUIRE(plain.ok());
    REQUIRE(strict.ok());
    for (size_t i = 0; i < 2; ++i)
        CHECK(plain.languages[i].fragment.source.source ==
              strict.languages[i].fragment.source.source);
}

TEST_CASE("strict_half_compares_two_half_values_at_16_bits", "[compile]") {
    // Widening binary16 to binary32 is exact, so a comparison of two half values has the same
    // result at 16 bits; writing it there spares the GPU two conversions (ACO on rdna2: the
    // flat default half variant 239 -> 233 instructions).
    Variant v = default_variant();
    REQUIRE_FALSE(set_choice(v, "precision", "half"));
    const VariantBuild b = build_variant(v, nullptr, EmitOptions{true});
    REQUIRE(b.ok());
    const std::string& glsl = b.languages[0].fragment.source.source;
    const std::string& hlsl = b.languages[1].fragment.source.source;
    // The Blinn-Phong guard: the half lobe's base against a half constant, in both languages.
    CHECK(glsl.find(" > float16_t(6.1035156e-05);") != std::string::npos);
    CHECK(hlsl.find(" > ((half)(6.1035156e-05));") != std::string::npos);
    // A 32-bit parameter against a half constant still compares at 32 bits.
    CHECK(glsl.find("params.refraction_shore_fade_depth > float(float16_t(0.0))") !=
          std::string::npos);
    CHECK(glsl.find(") > float(") == std::string::npos);
}
