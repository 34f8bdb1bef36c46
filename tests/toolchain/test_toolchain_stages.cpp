// Individual stages: where diagnostics come from and what they say.
#include <catch2/catch.hpp>

#include <string>

#include <spirv-tools/libspirv.hpp>

#include "watergen/toolchain/glslang_stage.h"
#include "watergen/toolchain/reflection_stage.h"
#include "watergen/toolchain/spirv_cross_stage.h"
#include "watergen/toolchain/spirv_tools_stage.h"
#include "watergen/toolchain/toolchain.h"

using namespace watergen;

namespace {

CompileRequest glsl_fragment(const char* source, const char* file = "water.frag") {
    CompileRequest r;
    r.language = SourceLanguage::Glsl;
    r.stage = ShaderStage::Fragment;
    r.source = source;
    r.file_name = file;
    return r;
}

const Diagnostic* first_error(const Diagnostics& ds) {
    for (const auto& d : ds)
        if (d.severity == Severity::Error) return &d;
    return nullptr;
}

const char* const kMinimal =
    "#version 450\nlayout(location = 0) out vec4 c;\nvoid main() { c = vec4(1.0); }\n";

} // namespace

TEST_CASE("glsl_undeclared_identifier_reports_its_line") {
    const SpirvResult r = compile_to_spirv(glsl_fragment(R"(#version 450
layout(location = 0) out vec4 color;

void main() {
    float a = 1.0;
    color = vec4(foo, a, a, 1.0);
}
)"));
    CHECK_FALSE(r.ok());
    CHECK(r.spirv.empty());
    const Diagnostic* e = first_error(r.diagnostics);
    REQUIRE(e != nullptr);
    CHECK(e->file == "water.frag");
    CHECK(e->line == 6);
    CHECK(e->column == 0);
    CHECK(e->node.empty());
    CHECK(e->message == "'foo' : undeclared identifier");
    // The "N compilation errors" summary is not repeated as a diagnostic.
    for (const auto& d : r.diagnostics)
        CHECK(d.message.find("compilation errors") == std::string::npos);
}

TEST_CASE("glsl_syntax_error_reports_its_line") {
    const SpirvResult r = compile_to_spirv(glsl_fragment(R"(#version 450
layout(location = 0) out vec4 color;
void main() {
    color = vec4(1.0)
    color.a = 0.5;
}
)"));
    CHECK_FALSE(r.ok());
    const Diagnostic* e = first_error(r.diagnostics);
    REQUIRE(e != nullptr);
    CHECK(e->line == 5); // glslang notices the missing ';' at the next token
    CHECK(e->message.find("syntax error") != std::string::npos);
}

TEST_CASE("hlsl_error_reports_its_line") {
    CompileRequest req;
    req.language = SourceLanguage::Hlsl;
    req.stage = ShaderStage::Fragment;
    req.file_name = "water.hlsl";
    req.source = "float4 main(float2 uv : TEXCOORD0) : SV_Target0 {\n"
                 "    float x = 1.0;\n"
                 "    return float4(uv, missing_value, x);\n"
                 "}\n";
    const SpirvResult r = compile_to_spirv(req);
    CHECK_FALSE(r.ok());
    const Diagnostic* e = first_error(r.diagnostics);
    REQUIRE(e != nullptr);
    CHECK(e->file == "water.hlsl");
    CHECK(e->line == 3);
    CHECK(e->message.find("missing_value") != std::string::npos);
}

TEST_CASE("hlsl_entry_point_comes_from_the_request") {
    CompileRequest req;
    req.language = SourceLanguage::Hlsl;
    req.stage = ShaderStage::Fragment;
    req.file_name = "water.hlsl";
    req.entry_point = "water_ps";
    req.source =
        "float4 water_ps(float2 uv : TEXCOORD0) : SV_Target0 { return float4(uv, 0.0, 1.0); }\n";
    const SpirvResult r = compile_to_spirv(req);
    REQUIRE(r.ok());
    const ReflectResult refl = reflect_spirv(r.spirv, ShaderStage::Fragment);
    CHECK(refl.diagnostics.empty());
    CHECK(refl.reflection.entry_point == "water_ps");
}

TEST_CASE("glslang_log_lines_become_diagnostics") {
    const Diagnostics ds = parse_glslang_log("WARNING: 0:3: 'x' : unused\n"
                                             "ERROR: 0:12: 'foo' : undeclared identifier\n"
                                             "ERROR: 0:14:7: 'bar' : with a column\n"
                                             "ERROR: Linking fragment stage: Missing entry point\n"
                                             "ERROR: 3 compilation errors.  No code generated.\n",
                                             "f.frag");
    REQUIRE(ds.size() == 4);
    CHECK(ds[0].severity == Severity::Warning);
    CHECK(ds[0].line == 3);
    CHECK(ds[1].severity == Severity::Error);
    CHECK(ds[1].line == 12);
    CHECK(ds[1].message == "'foo' : undeclared identifier");
    CHECK(ds[2].line == 14);
    CHECK(ds[2].column == 7);
    CHECK(ds[3].line == 0);
    CHECK(ds[3].message == "Linking fragment stage: Missing entry point");
    for (const auto& d : ds)
        CHECK(d.file == "f.frag");
}

TEST_CASE("check_glsl_accepts_330_and_300es_and_rejects_the_wrong_version") {
    const char* core = "#version 330\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
    const char* es =
        "#version 300 es\nprecision highp float;\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
    CHECK(check_glsl(core, ShaderStage::Fragment, GlslProfile::Core330, "a.330.glsl").empty());
    CHECK(check_glsl(es, ShaderStage::Fragment, GlslProfile::Es300, "a.300es.glsl").empty());

    const Diagnostics wrong =
        check_glsl(es, ShaderStage::Fragment, GlslProfile::Core330, "a.330.glsl");
    REQUIRE(has_errors(wrong));
    CHECK(wrong[0].line == 1);
    CHECK(wrong[0].message.find("expected '#version 330'") != std::string::npos);

    // layout(binding) is not 330 core: exactly what the SPIRV-Cross options must avoid.
    const char* with_binding =
        "#version 330\nlayout(binding = 1) uniform sampler2D t;\nout vec4 c;\n"
        "void main() { c = texture(t, vec2(0.5)); }\n";
    const Diagnostics bad =
        check_glsl(with_binding, ShaderStage::Fragment, GlslProfile::Core330, "b.330.glsl");
    REQUIRE(has_errors(bad));
    CHECK(first_error(bad)->line == 2);
}

TEST_CASE("spirv_val_rejects_a_broken_module") {
    SpirvResult r = compile_to_spirv(glsl_fragment(kMinimal));
    REQUIRE(r.ok());
    CHECK(validate_spirv(r.spirv, "m.spv").empty());
    r.spirv.resize(r.spirv.size() - 3); // cut the function body off
    const Diagnostics ds = validate_spirv(r.spirv, "m.spv");
    REQUIRE(has_errors(ds));
    CHECK(ds[0].file == "m.spv");
    CHECK(ds[0].message.rfind("spirv-val: ", 0) == 0);
    CHECK(count_instructions({}) == 0);
}

TEST_CASE("spirv_val_names_ids_in_its_messages") {
    // Validation runs without friendly names first; a module with messages is validated
    // again with them, so the message names the variable as the spirv-val CLI does.
    const char* const kStoreToInput = R"(OpCapability Shader
OpMemoryModel Logical GLSL450
OpEntryPoint Fragment %main "main" %water_height
OpExecutionMode %main OriginUpperLeft
OpName %water_height "water_height"
%void = OpTypeVoid
%fn = OpTypeFunction %void
%float = OpTypeFloat 32
%ptr = OpTypePointer Input %float
%water_height = OpVariable %ptr Input
%one = OpConstant %float 1
%main = OpFunction %void None %fn
%entry = OpLabel
OpStore %water_height %one
OpReturn
OpFunctionEnd
)";
    std::vector<uint32_t> spirv;
    REQUIRE(spvtools::SpirvTools(SPV_ENV_VULKAN_1_1).Assemble(kStoreToInput, &spirv));
    const Diagnostics ds = validate_spirv(spirv, "s.spv");
    REQUIRE(has_errors(ds));
    INFO(ds[0].message);
    CHECK(ds[0].message.find("[%water_height]") != std::string::npos); // not "[%2]"
}

TEST_CASE("spirv_cross_errors_become_diagnostics") {
    const std::vector<uint32_t> garbage = {0x07230203, 0x00010300, 0, 10, 0, 0xdeadbeef};
    const CrossResult cross = cross_compile(garbage, CrossTarget::Glsl330, "g.330.glsl");
    CHECK(cross.source.empty());
    REQUIRE(has_errors(cross.diagnostics));
    CHECK(cross.diagnostics[0].file == "g.330.glsl");
    CHECK(cross.diagnostics[0].message.rfind("spirv-cross: ", 0) == 0);

    const ReflectResult refl = reflect_spirv(garbage, ShaderStage::Fragment, "g.spv");
    CHECK(has_errors(refl.diagnostics));
}

TEST_CASE("reflecting_the_wrong_stage_is_an_error") {
    const SpirvResult r = compile_to_spirv(glsl_fragment(kMinimal));
    REQUIRE(r.ok());
    const ReflectResult refl = reflect_spirv(r.spirv, ShaderStage::Vertex, "m.spv");
    REQUIRE(has_errors(refl.diagnostics));
    CHECK(refl.diagnostics[0].message.find("vertex entry point") != std::string::npos);
}

TEST_CASE("toolchain_stops_at_the_failing_stage_and_names_it") {
    const ToolchainOutputs out =
        run_toolchain(glsl_fragment("#version 450\nvoid main() { nope(); }\n"));
    CHECK_FALSE(out.ok());
    CHECK(out.spirv.empty());
    CHECK(out.glsl330.empty());
    REQUIRE(has_errors(out.diagnostics));
    CHECK(first_error(out.diagnostics)->file == "water.frag");
    CHECK(first_error(out.diagnostics)->line == 2);
}

namespace {

// min16float and half arithmetic, as a water shader's precision=half variant would write it.
const char* const kHalfHlsl = R"(float4 main(float4 v : TEXCOORD0) : SV_Target0 {
    min16float a = (min16float)v.x;
    min16float b = (min16float)v.y;
    half c = (half)v.z;
    half d = (half)v.w;
    return float4(a * b, c + d, 0.0, 1.0);
}
)";

std::string hlsl_disassembly(const std::string& source, bool sixteen_bit_types) {
    CompileRequest req;
    req.language = SourceLanguage::Hlsl;
    req.stage = ShaderStage::Fragment;
    req.file_name = "half.hlsl";
    req.source = source;
    req.hlsl_16bit_types = sixteen_bit_types;
    const SpirvResult r = compile_to_spirv(req);
    for (const auto& d : r.diagnostics)
        UNSCOPED_INFO(d.message);
    REQUIRE(r.ok());
    return disassemble_spirv(r.spirv);
}

} // namespace

TEST_CASE("hlsl_16bit_types_make_half_and_min16float_binary16") {
    // Without the option glslang 12 computes both in 32 bits (min16float only as a
    // RelaxedPrecision hint); with it, both are OpTypeFloat 16 and the arithmetic is 16-bit.
    const std::string relaxed = hlsl_disassembly(kHalfHlsl, false);
    CHECK(relaxed.find("OpTypeFloat 16") == std::string::npos);
    CHECK(relaxed.find("RelaxedPrecision") != std::string::npos);
    CHECK(relaxed.find("OpFMul %float") != std::string::npos);

    const std::string sixteen = hlsl_disassembly(kHalfHlsl, true);
    CHECK(sixteen.find("OpCapability Float16") != std::string::npos);
    CHECK(sixteen.find("%half = OpTypeFloat 16") != std::string::npos);
    CHECK(sixteen.find("OpFMul %half") != std::string::npos);
    CHECK(sixteen.find("OpFAdd %half") != std::string::npos);
}

TEST_CASE("hlsl_float16_t_is_unknown_to_glslang_12") {
    // dxc spells the type float16_t; glslang 12's HLSL front end does not, with or without
    // 16-bit types, so emitted HLSL must say `half` (or min16float) to get binary16.
    for (bool sixteen_bit_types : {false, true}) {
        CompileRequest req;
        req.language = SourceLanguage::Hlsl;
        req.stage = ShaderStage::Fragment;
        req.file_name = "half.hlsl";
        req.source = "float4 main(float4 v : TEXCOORD0) : SV_Target0 {\n"
                     "    float16_t a = (float16_t)v.x;\n    return float4(a, 0.0, 0.0, 1.0);\n}\n";
        req.hlsl_16bit_types = sixteen_bit_types;
        const SpirvResult r = compile_to_spirv(req);
        CHECK_FALSE(r.ok());
        const Diagnostic* error = first_error(r.diagnostics);
        REQUIRE(error != nullptr);
        CHECK(error->line == 2);
        CHECK(error->message.find("float16_t") != std::string::npos);
    }
}
