// Reflection <-> JSON: deterministic text, lossless round trip, errors that name the key.
#include <catch2/catch.hpp>

#include <string>
#include <tuple>

#include "watergen/runtime/reflection.h"
#include "watergen/toolchain/glslang_stage.h"
#include "watergen/toolchain/reflection_stage.h"

using namespace watergen;

namespace {

Reflection sample_reflection() {
    Reflection r;
    r.stage = ShaderStage::Fragment;
    r.entry_point = "main";
    DescriptorBinding ubo;
    ubo.name = "WaterParams";
    ubo.kind = DescriptorKind::UniformBuffer;
    ubo.block_size = 96;
    ubo.members = {{"eye_position", "vec3", 0, 12},
                   {"water_level", "float", 12, 4},
                   {"deep_color", "vec4", 16, 16},
                   {"wave_directions", "vec4[4]", 32, 64, 4, 16}};
    DescriptorBinding sampler{"linear_clamp", 0, 1, DescriptorKind::Sampler, "", 0, {}};
    DescriptorBinding image{"scene_color", 0, 2, DescriptorKind::SampledImage, "2D", 0, {}};
    DescriptorBinding sky{"sky", 1, 0, DescriptorKind::CombinedImageSampler, "Cube", 0, {}};
    r.bindings = {ubo, sampler, image, sky};
    r.inputs = {{"uv", 0, "vec2"}, {"world_position", 1, "vec3"}};
    r.outputs = {{"frag_color", 0, "vec4"}};
    r.specialization_constants = {{0, "water_level", "float", -0.5, -100.0, 100.0},
                                  {1, "tint_x", "float", double(0.1f), 0.0, 1.0}};
    return r;
}

void check_equal(const DescriptorBinding& x, const DescriptorBinding& y) {
    CHECK(x.name == y.name);
    CHECK(x.set == y.set);
    CHECK(x.binding == y.binding);
    CHECK(x.kind == y.kind);
    CHECK(x.image_dim == y.image_dim);
    CHECK(x.block_size == y.block_size);
    REQUIRE(x.members.size() == y.members.size());
    for (size_t m = 0; m < x.members.size(); ++m) {
        CHECK(x.members[m].name == y.members[m].name);
        CHECK(x.members[m].type == y.members[m].type);
        CHECK(x.members[m].offset == y.members[m].offset);
        CHECK(x.members[m].size == y.members[m].size);
        CHECK(x.members[m].array_size == y.members[m].array_size);
        CHECK(x.members[m].array_stride == y.members[m].array_stride);
    }
}

void check_equal(const Reflection& a, const Reflection& b) {
    CHECK(a.stage == b.stage);
    CHECK(a.entry_point == b.entry_point);
    REQUIRE(a.push_constant.has_value() == b.push_constant.has_value());
    if (a.push_constant) check_equal(*a.push_constant, *b.push_constant);
    REQUIRE(a.bindings.size() == b.bindings.size());
    for (size_t i = 0; i < a.bindings.size(); ++i)
        check_equal(a.bindings[i], b.bindings[i]);
    auto same_vars = [](const std::vector<StageVariable>& p, const std::vector<StageVariable>& q) {
        REQUIRE(p.size() == q.size());
        for (size_t i = 0; i < p.size(); ++i) {
            CHECK(p[i].name == q[i].name);
            CHECK(p[i].location == q[i].location);
            CHECK(p[i].type == q[i].type);
        }
    };
    same_vars(a.inputs, b.inputs);
    same_vars(a.outputs, b.outputs);
    auto fields = [](const SpecializationConstant& c) {
        return std::tie(c.id, c.name, c.type, c.default_value, c.min, c.max);
    };
    REQUIRE(a.specialization_constants.size() == b.specialization_constants.size());
    for (size_t i = 0; i < a.specialization_constants.size(); ++i)
        CHECK(fields(a.specialization_constants[i]) == fields(b.specialization_constants[i]));
}

std::string error_for(const std::string& text) {
    std::string error;
    const auto r = reflection_from_json(text, &error);
    CHECK_FALSE(r.has_value());
    return error;
}

const char* const kValid = R"({"stage": "fragment", "entry_point": "main",
  "bindings": [{"name": "t", "set": 0, "binding": 1, "kind": "sampled_image", "image_dim": "2D"}],
  "inputs": [], "outputs": [{"name": "c", "location": 0, "type": "vec4"}]})";

} // namespace

TEST_CASE("reflection_json_round_trips") {
    const Reflection original = sample_reflection();
    const std::string text = reflection_to_json(original);
    std::string error;
    const auto back = reflection_from_json(text, &error);
    INFO(error);
    REQUIRE(back.has_value());
    check_equal(original, *back);
    CHECK(reflection_to_json(*back) == text);
}

TEST_CASE("reflection_json_is_sorted_indented_and_ends_with_a_newline") {
    const std::string text = reflection_to_json(sample_reflection());
    REQUIRE_FALSE(text.empty());
    CHECK(text.back() == '\n');
    CHECK(text.rfind("{\n  \"bindings\": [", 0) == 0); // keys sorted, 2-space indent
    CHECK(text.find("\"kind\": \"uniform_buffer\"") != std::string::npos);
    CHECK(text.find("\"stage\": \"fragment\"") != std::string::npos);
    // Array fields only on array members: older files stay as they were.
    CHECK(text.find("\"array_size\": 4") != std::string::npos);
    CHECK(text.find("\"array_stride\": 16") != std::string::npos);
    CHECK(text.find("\"array_size\": 0") == std::string::npos);
    CHECK(text.find('\t') == std::string::npos);
}

TEST_CASE("reflection_json_round_trips_a_reflected_shader") {
    CompileRequest req;
    req.stage = ShaderStage::Fragment;
    req.file_name = "t.frag";
    req.source = R"(#version 450
layout(set = 0, binding = 0, std140) uniform WaterParams { layout(offset = 0) vec3 eye; layout(offset = 12) float level; layout(offset = 16) float gains[3]; } p;
layout(set = 0, binding = 1) uniform sampler s;
layout(set = 0, binding = 2) uniform textureCube sky;
layout(location = 0) in vec3 dir;
layout(location = 0) out vec4 c;
void main() { c = texture(samplerCube(sky, s), dir + p.eye) * p.level * p.gains[int(dir.x)]; }
)";
    const SpirvResult spirv = compile_to_spirv(req);
    REQUIRE(spirv.ok());
    const ReflectResult refl = reflect_spirv(spirv.spirv, ShaderStage::Fragment, "t.frag.spv");
    REQUIRE(refl.diagnostics.empty());
    REQUIRE(refl.reflection.bindings.size() == 3);
    CHECK(refl.reflection.bindings[2].image_dim == "Cube");
    // A float array: one 16-byte register per element, std140's array stride.
    const auto& members = refl.reflection.bindings[0].members;
    REQUIRE(members.size() == 3);
    CHECK(members[0].array_size == 0);
    CHECK(members[2].type == "float[3]");
    CHECK(members[2].offset == 16);
    CHECK(members[2].size == 48);
    CHECK(members[2].array_size == 3);
    CHECK(members[2].array_stride == 16);
    CHECK(refl.reflection.bindings[0].block_size == 64);
    std::string error;
    const auto back = reflection_from_json(reflection_to_json(refl.reflection), &error);
    INFO(error);
    REQUIRE(back.has_value());
    check_equal(refl.reflection, *back);
}

TEST_CASE("reflection_from_json_accepts_omitted_optional_binding_fields") {
    std::string error;
    const auto r = reflection_from_json(kValid, &error);
    INFO(error);
    REQUIRE(r.has_value());
    CHECK(error.empty());
    REQUIRE(r->bindings.size() == 1);
    CHECK(r->bindings[0].block_size == 0);
    CHECK(r->bindings[0].members.empty());
}

TEST_CASE("reflection_from_json_names_the_bad_key") {
    CHECK(error_for("{ not json").rfind("(root): expected valid JSON", 0) == 0);
    CHECK(error_for("[1, 2]") == "(root): expected an object");
    CHECK(error_for(R"({"entry_point": "main", "bindings": [], "inputs": [], "outputs": []})")
              .rfind("stage: missing", 0) == 0);
    CHECK(
        error_for(
            R"({"stage": "geometry", "entry_point": "main", "bindings": [], "inputs": [], "outputs": []})") ==
        "stage: expected one of vertex, fragment, compute, tess_control, tess_evaluation; got "
        "\"geometry\"");

    std::string text = kValid;
    text.replace(text.find("\"binding\": 1"), 12, "\"binding\": \"one\"");
    CHECK(error_for(text) == "bindings[0].binding: expected an unsigned 32-bit integer");

    text = kValid;
    text.replace(text.find("\"location\": 0"), 13, "\"location\": -1");
    CHECK(error_for(text) == "outputs[0].location: expected an unsigned 32-bit integer");

    text = kValid;
    text.replace(text.find("\"sampled_image\""), 15, "\"texture\"");
    CHECK(error_for(text).rfind("bindings[0].kind: expected one of uniform_buffer,", 0) == 0);

    const std::string bad_member =
        R"({"stage": "fragment", "entry_point": "main", "inputs": [], "outputs": [],
      "bindings": [{"name": "B", "set": 0, "binding": 0, "kind": "uniform_buffer",
                    "members": [{"name": "a", "type": "float", "offset": 0, "size": 4}, {"name": "b", "type": "vec2"}]}]})";
    CHECK(error_for(bad_member) ==
          "bindings[0].members[1].offset: missing, expected an unsigned 32-bit integer");

    CHECK(
        error_for(
            R"({"stage": "vertex", "entry_point": "main", "bindings": [3], "inputs": [], "outputs": []})") ==
        "bindings[0]: expected an object");
    // A null error pointer is allowed.
    CHECK_FALSE(reflection_from_json("nope", nullptr).has_value());
}

TEST_CASE("reflection_json_round_trips_specialization_constants_of_a_reflected_shader") {
    CompileRequest req;
    req.stage = ShaderStage::Fragment;
    req.file_name = "t.frag";
    req.source = R"(#version 450
layout(constant_id = 7) const float tint_x = -2.5;
layout(constant_id = 3) const float gain = 0.1;
layout(constant_id = 5) const int steps = 4;
layout(location = 0) out vec4 c;
void main() { c = vec4(tint_x, gain, float(steps), 1.0); }
)";
    const SpirvResult spirv = compile_to_spirv(req);
    REQUIRE(spirv.ok());
    const ReflectResult refl = reflect_spirv(spirv.spirv, ShaderStage::Fragment, "t.frag.spv");
    REQUIRE(refl.diagnostics.empty());
    const auto& constants = refl.reflection.specialization_constants;
    REQUIRE(constants.size() == 3); // by id
    CHECK(constants[0].id == 3);
    CHECK(constants[0].name == "gain");
    CHECK(constants[0].type == "float");
    CHECK(constants[0].default_value == double(0.1f));
    CHECK(constants[1].name == "steps");
    CHECK(constants[1].type == "int");
    CHECK(constants[1].default_value == 4.0);
    CHECK(constants[2].id == 7);
    CHECK(constants[2].default_value == -2.5);
    CHECK(constants[2].min == 0.0); // not in SPIR-V
    const std::string text = reflection_to_json(refl.reflection);
    CHECK(text.find(R"("name": "tint_x")") != std::string::npos);
    std::string error;
    const auto back = reflection_from_json(text, &error);
    INFO(error);
    REQUIRE(back.has_value());
    check_equal(refl.reflection, *back);
    CHECK(reflection_to_json(*back) == text);
}

TEST_CASE("reflection_json_without_specialization_constants_keeps_its_form") {
    Reflection r = sample_reflection();
    r.specialization_constants.clear();
    const std::string text = reflection_to_json(r);
    CHECK(text.find("specialization") == std::string::npos);
    const auto back = reflection_from_json(kValid, nullptr);
    REQUIRE(back.has_value());
    CHECK(back->specialization_constants.empty());
}

TEST_CASE("reflection_from_json_names_a_bad_specialization_constant") {
    const std::string base = R"({"stage": "fragment", "entry_point": "main", "bindings": [],
  "inputs": [], "outputs": [], "specialization_constants": [)";
    CHECK(error_for(base + R"({"id": 0, "name": "a", "type": "float", "default": "x", "min": 0,
        "max": 1}]})") == "specialization_constants[0].default: expected a number");
    CHECK(error_for(base + R"({"id": 0, "name": "a", "type": "float", "default": 1, "min": 0,
        "max": 1}, {"id": -1}]})") ==
          "specialization_constants[1].id: expected an unsigned 32-bit integer");
    CHECK(error_for(base + R"({"id": 0, "name": "a", "type": "float", "default": 1,
        "min": 0}]})") == "specialization_constants[0].max: missing, expected a number");
    CHECK(error_for(base + "{}], \"x\": 1}").rfind("specialization_constants[0].id: missing", 0) ==
          0);
}

namespace {

// The sample with its parameter block as a push constant (a binding map of kind push_constant):
// the block leaves `bindings` for `push_constant`, same members and offsets.
Reflection push_constant_reflection() {
    Reflection r = sample_reflection();
    DescriptorBinding block = r.bindings.front();
    block.kind = DescriptorKind::PushConstant;
    r.bindings.erase(r.bindings.begin());
    r.push_constant = block;
    return r;
}

const char* const kPushBase = R"({"stage": "fragment", "entry_point": "main", "bindings": [],
  "inputs": [], "outputs": [], "push_constant": )";

} // namespace

TEST_CASE("reflection_json_round_trips_a_push_constant_block") {
    const Reflection original = push_constant_reflection();
    const std::string text = reflection_to_json(original);
    CHECK(text.find("\"push_constant\": {") != std::string::npos);
    CHECK(text.find("\"kind\": \"push_constant\"") != std::string::npos);
    std::string error;
    const auto back = reflection_from_json(text, &error);
    INFO(error);
    REQUIRE(back.has_value());
    REQUIRE(back->push_constant.has_value());
    CHECK(back->push_constant->name == "WaterParams");
    CHECK(back->push_constant->block_size == 96);
    CHECK(back->push_constant->members.size() == 4);
    check_equal(original, *back);
    CHECK(reflection_to_json(*back) == text);
    // Without one the key is absent: every file written before keeps its form.
    CHECK(reflection_to_json(sample_reflection()).find("push_constant") == std::string::npos);
    const auto none = reflection_from_json(kValid, &error);
    REQUIRE(none.has_value());
    CHECK_FALSE(none->push_constant.has_value());
}

TEST_CASE("reflection_from_json_names_a_bad_push_constant_block") {
    const std::string base = kPushBase;
    const std::string block = R"({"name": "P", "set": 0, "binding": 0, "kind": "push_constant",
        "block_size": 16, "members": [{"name": "a", "type": "vec4", "offset": 0, "size": 16}]})";
    std::string error;
    const auto good = reflection_from_json(base + block + "}", &error);
    INFO(error);
    REQUIRE(good.has_value());
    REQUIRE(good->push_constant.has_value());
    CHECK(good->push_constant->block_size == 16);

    auto with = [&](const std::string& from, const std::string& to) {
        std::string b = block;
        REQUIRE(b.find(from) != std::string::npos);
        b.replace(b.find(from), from.size(), to);
        return base + b + "}";
    };
    CHECK(error_for(base + "3}") == "push_constant: expected an object");
    CHECK(error_for(base + "[]}") == "push_constant: expected an object");
    CHECK(error_for(with(R"("kind": "push_constant")", R"("kind": "uniform_buffer")")) ==
          "push_constant.kind: expected one of push_constant; got \"uniform_buffer\"");
    CHECK(error_for(with(R"("set": 0)", R"("set": 1)")) ==
          "push_constant.set: 1; a push-constant block has set 0 and binding 0");
    CHECK(error_for(with(R"("binding": 0)", R"("binding": 2)")) ==
          "push_constant.binding: 2; a push-constant block has set 0 and binding 0");
    CHECK(error_for(with(R"("block_size": 16)", R"("block_size": 0)")) ==
          "push_constant.block_size: 0; expected 1 to 4096 bytes of push constants");
    CHECK(error_for(with(R"("block_size": 16)", R"("block_size": 4100)")) ==
          "push_constant.block_size: 4100; expected 1 to 4096 bytes of push constants");
    CHECK(error_for(with(R"("name": "P", )", "")) ==
          "push_constant.name: missing, expected a string");
    CHECK(error_for(with(R"("offset": 0)", R"("offset": "x")")) ==
          "push_constant.members[0].offset: expected an unsigned 32-bit integer");
    // A push constant is never a descriptor binding.
    std::string text = kValid;
    text.replace(text.find("\"sampled_image\""), 15, "\"push_constant\"");
    CHECK(error_for(text).rfind("bindings[0].kind: expected one of uniform_buffer,", 0) == 0);
}
