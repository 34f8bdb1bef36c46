// The parameter block as a push constant: BindingLayout's range (no descriptor, pool size or
// binding clash for it, the device's limit), VariantPipeline's range of its own (both stages'
// block, their stage flags) or the shared one, and draws on lavapipe whose colour comes from the
// pushed bytes, read back exactly: a RenderJob's uniforms bytes, and a UniformWriter's packed
// block drawn by name through a build's shared layout. Errors name the block; no validation
// message anywhere.
#include "runner_support.h"

#include <catch2/catch.hpp>

#include "watergen/runtime/binding_layout.h"
#include "watergen/runtime/uniform_writer.h"
#include "watergen/runtime/variant_pipeline.h"
#include "watergen/toolchain/glslang_stage.h"
#include "watergen/toolchain/reflection_stage.h"

#include <algorithm>
#include <cstring>

using namespace watergen;
using namespace watergen::test;

namespace {

// std140 as the generator keeps it for a push constant: `level` alone in the first register,
// rgb and a in the second, `tail` in the third. block_size 36: the pushed 36 bytes (rounded to
// 4), not UniformWriter's 48 (rounded to 16).
const std::string kWaterParamsBlock = R"(
layout(push_constant, std140) uniform WaterParams {
    layout(offset = 0) float level;
    layout(offset = 16) vec3 rgb;
    layout(offset = 28) float a;
    layout(offset = 32) float tail;
} p;
)";
const std::string kFragment = "#version 450" + kWaterParamsBlock + R"(
layout(location = 0) out vec4 color;
void main() { color = vec4(p.rgb * p.tail, p.a + p.level); }
)";

// The fullscreen triangle at depth `level`: the vertex stage reads the block too (a smaller
// view of it: 4 bytes).
const char* kVertex = R"(#version 450
layout(push_constant, std140) uniform WaterParams { layout(offset = 0) float level; } p;
void main() {
    vec2 q = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2));
    gl_Position = vec4(q * 2.0 - 1.0, p.level, 1.0);
}
)";

DescriptorBinding push_block(const std::string& name, uint32_t size,
                             std::vector<UniformMember> members) {
    DescriptorBinding b;
    b.name = name;
    b.kind = DescriptorKind::PushConstant;
    b.block_size = size;
    b.members = std::move(members);
    return b;
}

// The fragment block as the generator's reflection describes it.
DescriptorBinding fragment_block() {
    return push_block("WaterParams", 36,
                      {{"level", "float", 0, 4},
                       {"rgb", "vec3", 16, 12},
                       {"a", "float", 28, 4},
                       {"tail", "float", 32, 4}});
}

// GLSL with a push-constant block -> SPIR-V and reflection, whose push-constant block must be
// `block` (name and size).
CompiledStage compile_push_stage(ShaderStage stage, const std::string& source,
                                 const DescriptorBinding& block) {
    CompiledStage c = compile_glsl(stage, source);
    REQUIRE(c.reflection.push_constant);
    CHECK(c.reflection.push_constant->name == block.name);
    CHECK(c.reflection.push_constant->block_size == block.block_size);
    return c;
}

const CompiledStage& push_fragment() {
    static const CompiledStage s =
        compile_push_stage(ShaderStage::Fragment, kFragment, fragment_block());
    return s;
}

const CompiledStage& push_vertex() {
    static const CompiledStage s = compile_push_stage(
        ShaderStage::Vertex, kVertex, push_block("WaterParams", 4, {{"level", "float", 0, 4}}));
    return s;
}

// The block's bytes: level 0.25, rgb (1/16, 1/4, 3/8), a 0.5, tail 2; the first `size` bytes,
// zero-padded past the block's 36.
std::vector<uint8_t> block_values(size_t size = 36) {
    std::vector<uint8_t> bytes(std::max<size_t>(size, 36), 0);
    const float level = 0.25f, rgb[3] = {0.0625f, 0.25f, 0.375f}, a = 0.5f, tail = 2.0f;
    std::memcpy(bytes.data(), &level, 4);
    std::memcpy(bytes.data() + 16, rgb, 12);
    std::memcpy(bytes.data() + 28, &a, 4);
    std::memcpy(bytes.data() + 32, &tail, 4);
    bytes.resize(size);
    return bytes;
}

// rgb * tail, a + level: small dyadic rationals, exact whatever the driver does.
void check_pixels(const std::vector<float>& rgba, uint32_t w, uint32_t h) {
    REQUIRE(rgba.size() == size_t{w} * h * 4);
    const float expected[4] = {0.125f, 0.5f, 0.75f, 0.75f};
    size_t mismatches = 0;
    for (size_t i = 0; i < size_t{w} * h; ++i)
        for (int c = 0; c < 4; ++c)
            if (rgba[i * 4 + c] != expected[c] && mismatches++ < 5)
                UNSCOPED_INFO("pixel " << i << " channel " << c << ": got " << rgba[i * 4 + c]
                                       << " expected " << expected[c]);
    CHECK(mismatches == 0);
}

RenderJob push_job(const CompiledStage& vs, const CompiledStage& fs) {
    RenderJob job;
    job.vertex_spirv = vs.spirv;
    job.vertex_reflection = vs.reflection;
    job.fragment_spirv = fs.spirv;
    job.fragment_reflection = fs.reflection;
    job.width = 8;
    job.height = 4;
    job.timed_draws = 1;
    job.uniforms = block_values();
    return job;
}

// A map with the block as a push constant and a texture and sampler in set 0; the texture at
// set 0 binding 0, where the push constant's (absent) set and binding would clash with it.
BuildBindings push_map(uint32_t bytes = 36) {
    BuildBindings m;
    m.map = "push_test";
    MapSlot params;
    params.name = "WaterParams";
    params.kind = DescriptorKind::PushConstant;
    MapSlot texture;
    texture.name = "scene_color";
    texture.kind = DescriptorKind::SampledImage;
    MapSlot sampler;
    sampler.name = "linear_clamp";
    sampler.kind = DescriptorKind::Sampler;
    sampler.binding = 1;
    m.slots = {params, texture, sampler};
    m.push_constant_bytes = bytes;
    return m;
}

VkDevice device() {
    return shared_runner().device().device();
}

uint32_t device_max_push() {
    VkPhysicalDeviceProperties props{};
    vkGetPhysicalDeviceProperties(shared_runner().device().physical(), &props);
    return props.limits.maxPushConstantsSize;
}

void check_no_validation_messages() {
    const auto messages = shared_runner().validation_messages();
    INFO(joined(messages));
    CHECK(messages.empty());
}

} // namespace

TEST_CASE("a binding map's push constant is a range of the pipeline layout and no descriptor") {
    shared_runner().clear_validation_messages();
    std::string error;
    auto layout = BindingLayout::create(device(), push_map(), &error);
    INFO(error);
    REQUIRE(layout);
    const VkPushConstantRange* range = layout->push_constant_range();
    REQUIRE(range);
    CHECK(range->offset == 0);
    CHECK(range->size == 36);
    CHECK(range->stageFlags == (VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT));
    CHECK(layout->push_constant_block() == "WaterParams");
    // One set: the texture and the sampler; the push constant is in none.
    CHECK(layout->set_layouts().size() == 1);
    const auto pool = layout->pool_sizes(3);
    REQUIRE(pool.size() == 2);
    for (const VkDescriptorPoolSize& s : pool) {
        CHECK(s.type != VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
        CHECK(s.descriptorCount == 3);
    }

    // The push constant alone: no set at all.
    BuildBindings alone = push_map(128);
    alone.slots.resize(1);
    auto bare = BindingLayout::create(device(), alone, &error);
    REQUIRE(bare);
    CHECK(bare->set_layouts().empty());
    CHECK(bare->pool_sizes().empty());
    REQUIRE(bare->push_constant_range());
    CHECK(bare->push_constant_range()->size == 128);

    // A map without a push constant has no range.
    BuildBindings plain = push_map(0);
    plain.slots.erase(plain.slots.begin());
    auto none = BindingLayout::create(device(), plain, &error);
    REQUIRE(none);
    CHECK(none->push_constant_range() == nullptr);
    CHECK(none->push_constant_block().empty());
    check_no_validation_messages();
}

TEST_CASE("a push-constant range the device cannot hold or a map of two is refused") {
    std::string error;
    // Past the guaranteed 128 bytes unless the device's limit is given: both numbers named.
    CHECK_FALSE(BindingLayout::create(VK_NULL_HANDLE, push_map(256), &error));
    CHECK(error == "binding map 'push_test': push_constant_bytes 256 exceed the device's "
                   "maxPushConstantsSize 128");
    CHECK_FALSE(BindingLayout::create(VK_NULL_HANDLE, push_map(256), &error, 252));
    CHECK(error.find("256") != std::string::npos);
    CHECK(error.find("252") != std::string::npos);
    if (device_max_push() >= 256) {
        auto wide = BindingLayout::create(device(), push_map(256), &error, device_max_push());
        INFO(error);
        REQUIRE(wide);
        CHECK(wide->push_constant_range()->size == 256);
    }
    CHECK_FALSE(BindingLayout::create(VK_NULL_HANDLE, push_map(34), &error));
    CHECK(error == "binding map 'push_test': push_constant_bytes 34; expected a multiple of 4 "
                   "up to 4096");
    CHECK_FALSE(BindingLayout::create(VK_NULL_HANDLE, push_map(0), &error));
    CHECK(error == "binding map 'push_test': 'WaterParams' is a push constant but the map states "
                   "no push_constant_bytes");
    BuildBindings twice = push_map();
    twice.slots[1].kind = DescriptorKind::PushConstant;
    CHECK_FALSE(BindingLayout::create(VK_NULL_HANDLE, twice, &error));
    CHECK(error == "binding map 'push_test': 'WaterParams' and 'scene_color' are both push "
                   "constants; expected one push-constant block");
}

TEST_CASE("BindingLayout::check takes the map's push-constant block and refuses another") {
    std::string error;
    auto layout = BindingLayout::create(device(), push_map(), &error);
    INFO(error);
    REQUIRE(layout);
    Reflection r = push_fragment().reflection;
    CHECK(layout->check(r) == "");
    CHECK(layout->check(Reflection{}) == ""); // a stage without one

    Reflection bigger = r;
    bigger.push_constant->block_size = 40;
    CHECK(layout->check(bigger) ==
          "fragment stage: push-constant block 'WaterParams' (40 bytes) does not fit the "
          "push-constant range of 36 bytes of the binding map 'push_test'");
    Reflection other = r;
    other.push_constant->name = "Params";
    CHECK(layout->check(other) == "fragment stage: push-constant block 'Params' (36 bytes); the "
                                  "binding map 'push_test' pushes 'WaterParams'");
    Reflection texture = r;
    texture.push_constant->name = "scene_color";
    CHECK(layout->check(texture).find("pushes 'WaterParams' and has 'scene_color' as "
                                      "sampled_image at set 0 binding 0") != std::string::npos);
    // The block as a uniform buffer: a shader emitted with another map.
    Reflection ubo = r;
    DescriptorBinding b = *ubo.push_constant;
    b.kind = DescriptorKind::UniformBuffer;
    ubo.push_constant.reset();
    ubo.bindings = {b};
    CHECK(layout->check(ubo) ==
          "fragment stage: uniform_buffer 'WaterParams' at set 0 binding 0; the binding map "
          "'push_test' has it as a push constant (no descriptor): the shader was not emitted "
          "with this map");

    BuildBindings plain = push_map(0);
    plain.slots.erase(plain.slots.begin());
    auto none = BindingLayout::create(device(), plain, &error);
    REQUIRE(none);
    CHECK(none->check(r) == "fragment stage: push-constant block 'WaterParams' (36 bytes); the "
                            "binding map 'push_test' has no push-constant range");
}

TEST_CASE("a pipeline's own layout pushes both stages' block with the stages that read it") {
    shared_runner().clear_validation_messages();
    HeadlessDevice& gpu = shared_runner().device();
    const CompiledStage& vs = push_vertex();
    const CompiledStage& fs = push_fragment();
    std::string error;
    VariantPipelineDesc desc{
        &vs.spirv, &fs.spirv, &vs.reflection, &fs.reflection, gpu.render_pass(), 0, {}};
    auto both = VariantPipeline::create(gpu.device(), desc, &error);
    INFO(error);
    REQUIRE(both);
    REQUIRE(both->push_constant());
    CHECK(both->push_constant()->name == "WaterParams");
    CHECK(both->push_constant()->block_size == 36); // the larger: the fragment's
    CHECK(both->push_constant()->members.size() == 4);
    CHECK(both->push_constant_size() == 36);
    CHECK(both->push_constant_stages() ==
          (VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT));
    CHECK(both->set_layouts().empty());
    CHECK(both->pool_sizes().empty());

    const CompiledStage& plain_vs = fullscreen_vertex();
    desc.vertex_spirv = &plain_vs.spirv;
    desc.vertex_reflection = &plain_vs.reflection;
    auto fragment_only = VariantPipeline::create(gpu.device(), desc, &error);
    REQUIRE(fragment_only);
    CHECK(fragment_only->push_constant_stages() == VK_SHADER_STAGE_FRAGMENT_BIT);

    // The stages name two blocks: one range cannot serve both.
    Reflection renamed = vs.reflection;
    renamed.push_constant->name = "VertexParams";
    desc.vertex_spirv = &vs.spirv;
    desc.vertex_reflection = &renamed;
    CHECK_FALSE(VariantPipeline::create(gpu.device(), desc, &error));
    CHECK(error == "the push-constant block is 'VertexParams' in the vertex stage and "
                   "'WaterParams' in the fragment stage; expected one block");
    // Past the device's limit (as given).
    desc.vertex_reflection = &vs.reflection;
    desc.max_push_constants_size = 32;
    CHECK_FALSE(VariantPipeline::create(gpu.device(), desc, &error));
    CHECK(error == "push-constant block 'WaterParams' of 36 bytes exceeds the device's "
                   "maxPushConstantsSize 32");
    // A push constant among the descriptors: not a binding of any set.
    Reflection among = fs.reflection;
    among.bindings.push_back(*among.push_constant);
    desc.max_push_constants_size = 128;
    desc.fragment_reflection = &among;
    CHECK_FALSE(VariantPipeline::create(gpu.device(), desc, &error));
    CHECK(error.find("fragment stage: push-constant block 'WaterParams' among the descriptor "
                     "bindings") == 0);
    check_no_validation_messages();
}

TEST_CASE("a render job's uniforms bytes are pushed and read back exactly") {
    VulkanRunner& runner = shared_runner();
    runner.clear_validation_messages();
    // Both stages read the block; the vertex stage alone does not; 48 bytes as pack() gives.
    for (const CompiledStage* vs : {&push_vertex(), &fullscreen_vertex()}) {
        RenderJob job = push_job(*vs, push_fragment());
        for (size_t size : {36, 48}) {
            job.uniforms = block_values(size);
            const RenderResult r = runner.render(job);
            INFO(r.error);
            REQUIRE(r.ok);
            check_pixels(r.rgba, r.width, r.height);
            // The draws after the first repeat the recorded push.
            CHECK(r.draw_ms.size() == 1);
        }
    }
    check_no_validation_messages();
}

TEST_CASE("a render job's push block missing or short or beside a uniform buffer fails") {
    VulkanRunner& runner = shared_runner();
    runner.clear_validation_messages();
    RenderJob job = push_job(push_vertex(), push_fragment());
    job.uniforms.clear();
    RenderResult r = runner.render(job);
    CHECK_FALSE(r.ok);
    CHECK(r.error == "render: push-constant block 'WaterParams' is not supplied (36 bytes needed)");
    job.uniforms = block_values(32);
    r = runner.render(job);
    CHECK_FALSE(r.ok);
    CHECK(r.error == "render: push-constant block 'WaterParams' needs 36 bytes; 32 supplied");

    // One block of bytes cannot feed both a uniform buffer and the push constant.
    const CompiledStage fs = compile_push_stage(
        ShaderStage::Fragment,
        "#version 450" + kWaterParamsBlock +
            R"(layout(set = 0, binding = 0, std140) uniform Extra { vec4 gain; } e;
layout(location = 0) out vec4 color;
void main() { color = vec4(p.rgb * p.tail, p.a + p.level) * e.gain; }
)",
        fragment_block());
    REQUIRE(fs.reflection.bindings.size() == 1);
    job = push_job(push_vertex(), fs);
    r = runner.render(job);
    CHECK_FALSE(r.ok);
    CHECK(r.error == "render: shaders declare uniform block(s) Extra and push-constant block "
                     "'WaterParams'; the job's uniforms bytes can feed only one");
    check_no_validation_messages();
}

TEST_CASE("a variant's block packed by UniformWriter is pushed through the build's layout") {
    VulkanRunner& runner = shared_runner();
    runner.clear_validation_messages();
    HeadlessDevice& gpu = runner.device();
    std::string error;
    // The range is exactly the block's 36 bytes: pushing pack()'s 48 would be past it. Without
    // the map's sampler: lavapipe (Mesa 22.3) crashes drawing with a bound set whose sampler
    // was never written, though the pipeline does not read it; an unwritten texture is fine.
    BuildBindings map = push_map(36);
    map.slots.pop_back();
    auto layout = BindingLayout::create(gpu.device(), map, &error);
    INFO(error);
    REQUIRE(layout);
    const CompiledStage& vs = push_vertex();
    const CompiledStage& fs = push_fragment();
    VariantPipelineDesc desc{
        &vs.spirv, &fs.spirv, &vs.reflection, &fs.reflection, gpu.render_pass(), 0, {}};
    desc.layout = &*layout;
    auto pipeline = VariantPipeline::create(gpu.device(), desc, &error);
    REQUIRE(pipeline);
    CHECK(pipeline->layout() == layout->layout());
    CHECK(pipeline->push_constant_size() == 36);
    CHECK(pipeline->push_constant_stages() ==
          (VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT));

    BuildVariant v;
    v.key = "push";
    v.scene = "test";
    v.block_name = "WaterParams";
    v.parameters = {{"level", "float", 0, 0, {0.0}, 0.0, 1.0},
                    {"rgb", "vec3", 0, 16, {0.0, 0.0, 0.0}, 0.0, 1.0},
                    {"a", "float", 0, 28, {0.5}, 0.0, 1.0},
                    {"tail", "float", 0, 32, {2.0}, 0.0, 4.0}};
    UniformWriter writer(v);
    CHECK(writer.set("level", 0.25f).ok);
    CHECK(writer.set("rgb", {0.0625f, 0.25f, 0.375f}).ok);
    const auto packed = writer.pack(fs.reflection, &error);
    INFO(error);
    REQUIRE(packed);
    CHECK(packed->size() == 48);
    CHECK(*packed == block_values(48));

    HeadlessDraw draw;
    draw.width = 4;
    draw.height = 4;
    draw.uniforms = {{"WaterParams", *packed}};
    const std::vector<float> rgba = gpu.draw(*pipeline, draw, &error);
    INFO(error);
    check_pixels(rgba, 4, 4);

    draw.uniforms.clear();
    CHECK(gpu.draw(*pipeline, draw, &error).empty());
    CHECK(error == "push-constant block 'WaterParams' is not supplied (36 bytes needed)");

    // A writer of another block name finds no block to pack.
    BuildVariant named = v;
    named.block_name = "Params";
    CHECK_FALSE(UniformWriter(named).pack(fs.reflection, &error));
    CHECK(error.find("no uniform block or push-constant block 'Params'") != std::string::npos);
    check_no_validation_messages();
}

TEST_CASE("a compute job with a push-constant block is refused naming it") {
    VulkanRunner& runner = shared_runner();
    runner.clear_validation_messages();
    CompiledStage cs = compile_glsl(ShaderStage::Compute, R"(#version 450
layout(local_size_x = 1) in;
layout(set = 0, binding = 0) writeonly buffer Outputs { float r[]; } outputs;
void main() { outputs.r[gl_GlobalInvocationID.x] = 1.0; }
)");
    ComputeJob job;
    job.spirv = cs.spirv;
    job.reflection = cs.reflection;
    job.reflection.push_constant = fragment_block();
    job.output_sizes["Outputs"] = 16;
    const ComputeResult result = runner.run_compute(job);
    CHECK_FALSE(result.ok);
    CHECK(result.error == "compute: push-constant block 'WaterParams': a compute job binds its "
                          "uniforms as a uniform buffer only");
    check_no_validation_messages();
}
