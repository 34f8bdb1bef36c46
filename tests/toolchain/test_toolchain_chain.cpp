// The whole in-process chain on equivalent GLSL and HLSL shaders, as the emitters write them:
// separate textures + one sampler, one uniform block with explicit offsets.
#include <catch2/catch.hpp>

#include <string>
#include <thread>

#include "watergen/toolchain/reflection_stage.h"
#include "watergen/toolchain/spirv_tools_stage.h"
#include "watergen/toolchain/toolchain.h"

using namespace watergen;

namespace {

const char* const kWaterGlsl = R"(#version 450
layout(set = 0, binding = 0, std140) uniform WaterParams {
    layout(offset = 0) vec3 eye_position;
    layout(offset = 12) float water_level;
    layout(offset = 16) vec3 sun_direction;
    layout(offset = 28) float time;
    layout(offset = 32) vec4 deep_color;
    layout(offset = 48) mat4 view_proj;
} params;
layout(set = 0, binding = 1) uniform sampler linear_clamp;
layout(set = 0, binding = 2) uniform texture2D scene_color;
layout(set = 0, binding = 3) uniform texture2D normal_map;

layout(location = 0) in vec2 uv;
layout(location = 1) in vec3 world_position;
layout(location = 0) out vec4 frag_color;

float fresnel_schlick(float cos_theta) {
    float f0 = 0.02;
    return f0 + (1.0 - f0) * pow(1.0 - clamp(cos_theta, 0.0, 1.0), 5.0);
}

void main() {
    vec2 scroll = vec2(params.time * 0.03, params.time * 0.017);
    vec3 n = texture(sampler2D(normal_map, linear_clamp), uv + scroll).xyz * 2.0 - 1.0;
    n = normalize(vec3(n.x, 1.0, n.y));
    vec3 view_dir = normalize(params.eye_position - world_position);
    float f = fresnel_schlick(dot(n, view_dir));
    vec4 clip = params.view_proj * vec4(world_position + n * 0.05, 1.0);
    vec2 refr_uv = clip.xy / clip.w * 0.5 + 0.5;
    vec3 refraction = texture(sampler2D(scene_color, linear_clamp), refr_uv).rgb;
    float depth = max(params.water_level - world_position.y, 0.0);
    vec3 water = mix(refraction, params.deep_color.rgb, clamp(depth * 0.2, 0.0, 1.0));
    vec3 h = normalize(view_dir + params.sun_direction);
    float spec = pow(max(dot(n, h), 0.0), 256.0);
    frag_color = vec4(mix(water, vec3(1.0), f) + spec, 1.0);
}
)";

// Same shader in HLSL.
const char* const kWaterHlsl = R"([[vk::binding(0, 0)]] cbuffer WaterParams {
    float3 eye_position : packoffset(c0);
    float water_level : packoffset(c0.w);
    float3 sun_direction : packoffset(c1);
    float time : packoffset(c1.w);
    float4 deep_color : packoffset(c2);
    float4x4 view_proj : packoffset(c3);
};
[[vk::binding(1, 0)]] SamplerState linear_clamp;
[[vk::binding(2, 0)]] Texture2D scene_color;
[[vk::binding(3, 0)]] Texture2D normal_map;

float fresnel_schlick(float cos_theta) {
    float f0 = 0.02;
    return f0 + (1.0 - f0) * pow(1.0 - saturate(cos_theta), 5.0);
}

float3 sample_normal(Texture2D tex, SamplerState s, float2 at) {
    return tex.Sample(s, at).xyz * 2.0 - 1.0;
}

float4 main(float2 uv : TEXCOORD0, float3 world_position : TEXCOORD1) : SV_Target0 {
    float2 scroll = float2(time * 0.03, time * 0.017);
    float3 n = sample_normal(normal_map, linear_clamp, uv + scroll);
    n = normalize(float3(n.x, 1.0, n.y));
    float3 view_dir = normalize(eye_position - world_position);
    float f = fresnel_schlick(dot(n, view_dir));
    float4 clip = mul(view_proj, float4(world_position + n * 0.05, 1.0));
    float2 refr_uv = clip.xy / clip.w * 0.5 + 0.5;
    float3 refraction = scene_color.Sample(linear_clamp, refr_uv).rgb;
    float depth = max(water_level - world_position.y, 0.0);
    float3 water = lerp(refraction, deep_color.rgb, saturate(depth * 0.2));
    float3 h = normalize(view_dir + sun_direction);
    float spec = pow(max(dot(n, h), 0.0), 256.0);
    return float4(lerp(water, float3(1.0, 1.0, 1.0), f) + spec, 1.0);
}
)";

const char* const kVertexGlsl = R"(#version 450
layout(set = 0, binding = 0, std140) uniform WaterParams {
    layout(offset = 0) mat4 view_proj;
} params;
layout(location = 0) in vec3 position;
layout(location = 0) out vec2 uv;
void main() {
    uv = position.xz * 0.5 + 0.5;
    gl_Position = params.view_proj * vec4(position, 1.0);
}
)";

const char* const kVertexHlsl = R"([[vk::binding(0, 0)]] cbuffer WaterParams {
    float4x4 view_proj : packoffset(c0);
};
struct VsOut { float2 uv : TEXCOORD0; float4 position : SV_Position; };
VsOut main(float3 position : POSITION0) {
    VsOut o;
    o.uv = position.xz * 0.5 + 0.5;
    o.position = mul(view_proj, float4(position, 1.0));
    return o;
}
)";

CompileRequest request(SourceLanguage language, ShaderStage stage, const char* source,
                       const char* file) {
    CompileRequest r;
    r.language = language;
    r.stage = stage;
    r.source = source;
    r.file_name = file;
    return r;
}

std::string describe(const Diagnostics& ds) {
    std::string s;
    for (const auto& d : ds)
        s += d.file + ":" + std::to_string(d.line) + ": " +
             (d.severity == Severity::Error ? "error: " : "note/warning: ") + d.message + "\n";
    return s;
}

void require_chain_ok(const ToolchainOutputs& out) {
    INFO(describe(out.diagnostics));
    REQUIRE(out.ok());
    for (const auto& d : out.diagnostics)
        CHECK(d.severity == Severity::Note); // no warnings either
    CHECK_FALSE(out.spirv.empty());
    CHECK_FALSE(out.spirv_optimized.empty());
    CHECK(out.instruction_count > 0);
    CHECK(out.instruction_count_optimized > 0);
    CHECK(out.glsl330.find("#version 330") != std::string::npos);
    CHECK(out.essl300.find("#version 300 es") != std::string::npos);
    CHECK(out.msl.find("#include <metal_stdlib>") != std::string::npos);
}

void check_same_bindings(const Reflection& a, const Reflection& b) {
    REQUIRE(a.bindings.size() == b.bindings.size());
    for (size_t i = 0; i < a.bindings.size(); ++i) {
        const DescriptorBinding& x = a.bindings[i];
        const DescriptorBinding& y = b.bindings[i];
        INFO("binding " << i << ": " << x.name << " vs " << y.name);
        CHECK(x.name == y.name);
        CHECK(x.set == y.set);
        CHECK(x.binding == y.binding);
        CHECK(x.kind == y.kind);
        CHECK(x.image_dim == y.image_dim);
        CHECK(x.block_size == y.block_size);
        REQUIRE(x.members.size() == y.members.size());
        for (size_t m = 0; m < x.members.size(); ++m) {
            INFO("member " << x.members[m].name);
            CHECK(x.members[m].name == y.members[m].name);
            CHECK(x.members[m].type == y.members[m].type);
            CHECK(x.members[m].offset == y.members[m].offset);
            CHECK(x.members[m].size == y.members[m].size);
        }
    }
}

} // namespace

TEST_CASE("glsl_fragment_shader_goes_through_the_whole_chain") {
    const ToolchainOutputs out = run_toolchain(
        request(SourceLanguage::Glsl, ShaderStage::Fragment, kWaterGlsl, "water.frag"));
    require_chain_ok(out);
    // Combined samplers carry the texture's name so GL engines can bind them by name.
    CHECK(out.glsl330.find("uniform sampler2D scene_color;") != std::string::npos);
    CHECK(out.glsl330.find("uniform sampler2D normal_map;") != std::string::npos);
    CHECK(out.glsl330.find("binding") == std::string::npos);
    CHECK(out.essl300.find("precision highp float;") != std::string::npos);
}

TEST_CASE("hlsl_fragment_shader_is_legalized_and_goes_through_the_whole_chain") {
    const ToolchainOutputs out = run_toolchain(
        request(SourceLanguage::Hlsl, ShaderStage::Fragment, kWaterHlsl, "water.hlsl"));
    require_chain_ok(out);
    CHECK(validate_spirv(out.spirv, "water.hlsl.spv").empty());
    CHECK(out.glsl330.find("uniform sampler2D scene_color;") != std::string::npos);
}

TEST_CASE("glsl_and_hlsl_paths_reflect_identical_bindings") {
    const ToolchainOutputs glsl = run_toolchain(
        request(SourceLanguage::Glsl, ShaderStage::Fragment, kWaterGlsl, "water.frag"));
    const ToolchainOutputs hlsl = run_toolchain(
        request(SourceLanguage::Hlsl, ShaderStage::Fragment, kWaterHlsl, "water.hlsl"));
    require_chain_ok(glsl);
    require_chain_ok(hlsl);
    check_same_bindings(glsl.reflection, hlsl.reflection);

    // packoffset and layout(offset) both land where the emitter put them.
    const Reflection& r = hlsl.reflection;
    REQUIRE(r.bindings.size() == 4);
    const DescriptorBinding& ubo = r.bindings[0];
    CHECK(ubo.name == "WaterParams");
    CHECK(ubo.kind == DescriptorKind::UniformBuffer);
    CHECK(ubo.block_size == 112);
    REQUIRE(ubo.members.size() == 6);
    CHECK(ubo.members[0].name == "eye_position");
    CHECK(ubo.members[0].type == "vec3");
    CHECK(ubo.members[0].offset == 0);
    CHECK(ubo.members[1].name == "water_level");
    CHECK(ubo.members[1].offset == 12);
    CHECK(ubo.members[3].name == "time");
    CHECK(ubo.members[3].offset == 28);
    CHECK(ubo.members[5].type == "mat4");
    CHECK(ubo.members[5].offset == 48);
    CHECK(ubo.members[5].size == 64);
    CHECK(r.bindings[1].name == "linear_clamp");
    CHECK(r.bindings[1].kind == DescriptorKind::Sampler);
    CHECK(r.bindings[2].name == "scene_color");
    CHECK(r.bindings[2].kind == DescriptorKind::SampledImage);
    CHECK(r.bindings[2].image_dim == "2D");
    CHECK(r.bindings[3].name == "normal_map");

    // Stage inputs agree too (locations come from declaration order in HLSL).
    REQUIRE(glsl.reflection.inputs.size() == 2);
    REQUIRE(hlsl.reflection.inputs.size() == 2);
    for (size_t i = 0; i < 2; ++i) {
        CHECK(glsl.reflection.inputs[i].name == hlsl.reflection.inputs[i].name);
        CHECK(glsl.reflection.inputs[i].location == hlsl.reflection.inputs[i].location);
        CHECK(glsl.reflection.inputs[i].type == hlsl.reflection.inputs[i].type);
    }
    REQUIRE(hlsl.reflection.outputs.size() == 1);
    CHECK(hlsl.reflection.outputs[0].type == "vec4");
    CHECK(hlsl.reflection.outputs[0].location == 0);
}

TEST_CASE("vertex_shaders_go_through_the_chain_without_reflecting_builtins") {
    for (const auto& req :
         {request(SourceLanguage::Glsl, ShaderStage::Vertex, kVertexGlsl, "water.vert"),
          request(SourceLanguage::Hlsl, ShaderStage::Vertex, kVertexHlsl, "water_vs.hlsl")}) {
        INFO(req.file_name);
        const ToolchainOutputs out = run_toolchain(req);
        require_chain_ok(out);
        CHECK(out.reflection.stage == ShaderStage::Vertex);
        REQUIRE(out.reflection.inputs.size() == 1);
        CHECK(out.reflection.inputs[0].type == "vec3");
        REQUIRE(out.reflection.outputs.size() == 1); // gl_Position / SV_Position is not listed
        CHECK(out.reflection.outputs[0].type == "vec2");
        // GLSL 330 links varyings by name: HLSL's "@entryPointOutput.uv" must come out as "uv".
        CHECK(out.reflection.outputs[0].name == "uv");
        CHECK(out.glsl330.find("out vec2 uv;") != std::string::npos);
    }
}

TEST_CASE("optimizer_removes_dead_code") {
    const char* dead = R"(#version 450
layout(location = 0) out vec4 color;
void main() {
    float unused = 0.0;
    for (int i = 0; i < 8; ++i) unused += sin(float(i) * 0.3);
    vec4 also_unused = vec4(unused) * 2.0;
    color = vec4(0.25, 0.5, 0.75, 1.0);
}
)";
    const ToolchainOutputs out =
        run_toolchain(request(SourceLanguage::Glsl, ShaderStage::Fragment, dead, "dead.frag"));
    require_chain_ok(out);
    CHECK(out.instruction_count_optimized < out.instruction_count);
    CHECK(count_instructions(out.spirv) == out.instruction_count);
    CHECK(disassemble_spirv(out.spirv_optimized).find("OpEntryPoint Fragment") !=
          std::string::npos);
}

TEST_CASE("two_threads_compile_at_once_after_warm_up") {
    glslang_warm_up();
    const ToolchainOutputs reference = run_toolchain(
        request(SourceLanguage::Glsl, ShaderStage::Fragment, kWaterGlsl, "water.frag"));
    require_chain_ok(reference);

    constexpr int kRounds = 4;
    bool ok[2] = {true, true};
    auto work = [&](int t) {
        for (int i = 0; i < kRounds; ++i) {
            const bool hlsl = (i + t) % 2 == 1;
            const ToolchainOutputs out =
                run_toolchain(hlsl ? request(SourceLanguage::Hlsl, ShaderStage::Fragment,
                                             kWaterHlsl, "water.hlsl")
                                   : request(SourceLanguage::Glsl, ShaderStage::Fragment,
                                             kWaterGlsl, "water.frag"));
            ok[t] = ok[t] && out.ok() && (hlsl || out.spirv == reference.spirv);
        }
    };
    std::thread a(work, 0), b(work, 1);
    a.join();
    b.join();
    CHECK(ok[0]);
    CHECK(ok[1]);
}

TEST_CASE("unused_descriptors_are_left_out_of_reflection_in_both_paths") {
    // glslang's HLSL path drops the unused texture, its GLSL path keeps it; reflection must
    // still agree. The unused block member stays: it is part of the block's layout.
    const char* glsl = R"(#version 450
layout(set = 0, binding = 4) uniform texture2D unused_texture;
layout(set = 0, binding = 0, std140) uniform Params {
    layout(offset = 0) float level;
    layout(offset = 4) float unused_member;
} params;
layout(location = 0) in vec2 uv;
layout(location = 1) in vec3 unread;
layout(location = 0) out vec4 color;
void main() { color = vec4(uv, params.level, 1.0); }
)";
    const char* hlsl = R"([[vk::binding(4, 0)]] Texture2D unused_texture;
[[vk::binding(0, 0)]] cbuffer Params {
    float level : packoffset(c0);
    float unused_member : packoffset(c0.y);
};
float4 main(float2 uv : TEXCOORD0, float3 unread : TEXCOORD1) : SV_Target0 { return float4(uv, level, 1.0); }
)";
    const ToolchainOutputs g =
        run_toolchain(request(SourceLanguage::Glsl, ShaderStage::Fragment, glsl, "u.frag"));
    const ToolchainOutputs h =
        run_toolchain(request(SourceLanguage::Hlsl, ShaderStage::Fragment, hlsl, "u.hlsl"));
    require_chain_ok(g);
    require_chain_ok(h);
    check_same_bindings(g.reflection, h.reflection);
    REQUIRE(g.reflection.bindings.size() == 1);
    REQUIRE(g.reflection.bindings[0].members.size() == 2);
    CHECK(g.reflection.bindings[0].members[1].offset == 4);
    // The HLSL path also removes the unread input, so neither path lists it.
    REQUIRE(g.reflection.inputs.size() == 1);
    REQUIRE(h.reflection.inputs.size() == 1);
    CHECK(g.reflection.inputs[0].name == h.reflection.inputs[0].name);
}

TEST_CASE("hlsl_struct_holding_a_texture_is_legalized_into_valid_spirv") {
    // Without legalisation glslang emits OpTypeStruct { image, float }, which Vulkan
    // forbids (VUID-StandaloneSpirv-None-04667); glslangValidator -Od shows the failure.
    const char* hlsl = R"([[vk::binding(2, 0)]] Texture2D scene_color;
[[vk::binding(1, 0)]] SamplerState linear_clamp;
struct Layer { Texture2D tex; float weight; };
float4 shade(Layer layer, float2 at) { return layer.tex.Sample(linear_clamp, at) * layer.weight; }
float4 main(float2 uv : TEXCOORD0) : SV_Target0 {
    Layer layer;
    layer.tex = scene_color;
    layer.weight = 0.5;
    return shade(layer, uv);
}
)";
    const SpirvResult compiled =
        compile_to_spirv(request(SourceLanguage::Hlsl, ShaderStage::Fragment, hlsl, "l.hlsl"));
    INFO(describe(compiled.diagnostics));
    REQUIRE(compiled.ok());
    CHECK(validate_spirv(compiled.spirv, "l.hlsl.spv").empty());
    const ToolchainOutputs out =
        run_toolchain(request(SourceLanguage::Hlsl, ShaderStage::Fragment, hlsl, "l.hlsl"));
    require_chain_ok(out);
    REQUIRE(out.reflection.bindings.size() == 2);
    CHECK(out.reflection.bindings[1].name == "scene_color");
}

TEST_CASE("compute_shaders_get_msl_but_no_gl_targets") {
    const char* compute = R"(#version 450
layout(local_size_x = 64) in;
layout(set = 0, binding = 0, std430) buffer Heights { float height[]; } heights;
void main() { heights.height[gl_GlobalInvocationID.x] *= 0.5; }
)";
    const ToolchainOutputs out =
        run_toolchain(request(SourceLanguage::Glsl, ShaderStage::Compute, compute, "h.comp"));
    INFO(describe(out.diagnostics));
    REQUIRE(out.ok());
    CHECK(out.glsl330.empty());
    CHECK(out.essl300.empty());
    CHECK(out.msl.find("kernel void") != std::string::npos);
    REQUIRE(out.reflection.bindings.size() == 1);
    CHECK(out.reflection.bindings[0].kind == DescriptorKind::StorageBuffer);
    CHECK(out.reflection.bindings[0].name == "Heights");
    REQUIRE(out.reflection.bindings[0].members.size() == 1);
    CHECK(out.reflection.bindings[0].members[0].type == "float[]");
}
