#include <catch2/catch.hpp>

#include <filesystem>

#include "watergen/ir/core/dsl.h"
#include "watergen/pipeline/output/output_writer.h"
#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/toolchain/glslang_stage.h"

using namespace watergen;

TEST_CASE("ill_typed_description_names_the_node_and_writes_nothing", "[diagnostics]") {
    WaterShader shader = build_water_shader(default_variant());
    Graph& g = shader.fragment;
    {
        OriginScope scope(g, "foam.broken");
        Expr v3 = varying(g, "v_uv", Type::Vec2); // same leaf as the shader's uv
        Expr bad = constant(g, {1.0, 0.0, 0.0}) + v3;
        g.set_output("color", vec4(bad, constant(g, 1.0)).id());
    }
    const VariantBuild b = build_shader(std::move(shader));
    CHECK_FALSE(b.ok());
    REQUIRE_FALSE(b.diagnostics.empty());
    CHECK(b.diagnostics[0].node == "foam.broken");
    CHECK(b.diagnostics[0].message == "+: operand types differ (got vec3, vec2)");
    CHECK(format_diagnostic(b.diagnostics[0]) ==
          "watergen: error: +: operand types differ (got vec3, vec2) [node: foam.broken]");
    CHECK(variant_files(b).empty());
    CHECK(b.languages[0].fragment.source.source.empty()); // never emitted
}

TEST_CASE("glslang_errors_map_back_to_the_emitting_node", "[diagnostics]") {
    const WaterShader shader = build_water_shader(default_variant());
    Diagnostics ds;
    EmittedShader frag =
        emit_fragment(shader.fragment, Language::Glsl, "water.frag.glsl", "test", ds);
    REQUIRE(ds.empty());
    // Break the line that computes Schlick's R0, as an emitter bug would.
    const std::string needle = "float fresnel_r0 = ";
    const size_t at = frag.source.find(needle);
    REQUIRE(at != std::string::npos);
    frag.source.insert(at + needle.size(), "undeclared_symbol + ");
    const int line =
        1 + static_cast<int>(
                std::count(frag.source.begin(), frag.source.begin() + static_cast<long>(at), '\n'));
    SpirvResult r = compile_to_spirv(
        {SourceLanguage::Glsl, ShaderStage::Fragment, frag.source, frag.file_name, "main"});
    REQUIRE_FALSE(r.ok());
    attribute_to_nodes(frag, r.diagnostics);
    bool found = false;
    for (const auto& d : r.diagnostics)
        if (d.line == line) {
            found = true;
            CHECK(d.node == "fresnel.schlick");
            CHECK(d.file == "water.frag.glsl");
        }
    CHECK(found);
}

TEST_CASE("failed_write_leaves_previous_output_intact", "[diagnostics]") {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / "watergen-atomic-test" / "out";
    fs::remove_all(dir.parent_path());
    REQUIRE_FALSE(write_directory_atomically(dir, {{"a.txt", "first"}}));
    // A relative path that escapes into a missing, unwritable place fails midway.
    const auto e = write_directory_atomically(dir, {{"b.txt", "second"}, {"sub/\0bad", "x"}});
    (void)e;
    CHECK(fs::exists(dir / "a.txt"));
    REQUIRE_FALSE(write_directory_atomically(dir, {{"c.txt", "third"}}));
    CHECK(fs::exists(dir / "c.txt"));
    CHECK_FALSE(fs::exists(dir / "a.txt"));
    int leftovers = 0;
    for (const auto& entry : fs::directory_iterator(dir.parent_path()))
        leftovers += entry.path() != dir;
    CHECK(leftovers == 0);
    fs::remove_all(dir.parent_path());
}
