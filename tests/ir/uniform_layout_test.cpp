#include <catch2/catch.hpp>

#include <cstring>

#include "watergen/ir/emit/uniform_layout.h"

using namespace watergen;

namespace {
Parameter p(const char* name, Type t) {
    return {.name = name,
            .type = t,
            .default_value = std::vector<double>(static_cast<size_t>(component_count(t)), 0.0),
            .max = 1};
}
uint32_t offset_of(const UniformLayout& l, const std::string& name) {
    for (const auto& m : l.members)
        if (m.name == name) return m.offset;
    return UINT32_MAX;
}
} // namespace

TEST_CASE("floats_fill_the_tail_of_vec3_registers", "[layout]") {
    Diagnostics ds;
    const auto l = layout_uniforms(
        {p("a", Type::Float), p("v", Type::Vec3), p("b", Type::Float), p("w", Type::Vec3)}, ds);
    CHECK(ds.empty());
    CHECK(offset_of(l, "v") == 0);
    CHECK(offset_of(l, "w") == 16);
    CHECK(offset_of(l, "a") == 12);
    CHECK(offset_of(l, "b") == 28);
    CHECK(l.size == 32);
}

TEST_CASE("no_member_straddles_a_16_byte_register", "[layout]") {
    Diagnostics ds;
    const auto l = layout_uniforms({p("f", Type::Float), p("u", Type::Vec2), p("g", Type::Float),
                                    p("q", Type::Vec2), p("h", Type::Float), p("c", Type::Vec4)},
                                   ds);
    for (const auto& m : l.members) {
        const uint32_t size = static_cast<uint32_t>(component_count(m.type)) * 4;
        CHECK(m.offset / 16 == (m.offset + size - 1) / 16);
        // std140 base alignment: vec2 on 8, vec3/vec4 on 16.
        CHECK(m.offset % (m.type == Type::Vec2 ? 8 : m.type == Type::Float ? 4 : 16) == 0);
    }
    CHECK(l.size % 16 == 0);
    CHECK(std::is_sorted(
        l.members.begin(), l.members.end(),
        [](const UniformSlot& a, const UniformSlot& b) { return a.offset < b.offset; }));
}

TEST_CASE("matrix_parameters_are_rejected", "[layout]") {
    Diagnostics ds;
    Parameter m{.name = "m",
                .type = Type::Mat3,
                .default_value = std::vector<double>(9, 0.0),
                .max = 1,
                .origin = "node.x"};
    layout_uniforms({m}, ds);
    REQUIRE(ds.size() == 1);
    CHECK(ds[0].node == "node.x");
}

TEST_CASE("pack_writes_defaults_as_floats_at_their_offsets", "[layout]") {
    Diagnostics ds;
    std::vector<Parameter> params = {
        {.name = "v", .type = Type::Vec3, .default_value = {1.0, 2.0, 3.0}, .max = 9},
        {.name = "s", .type = Type::Float, .default_value = {0.5}, .max = 9}};
    const auto l = layout_uniforms(params, ds);
    const auto bytes = pack_uniforms(l, params);
    REQUIRE(bytes.size() == 16);
    float f[4];
    std::memcpy(f, bytes.data(), 16);
    CHECK(f[0] == 1.0f);
    CHECK(f[2] == 3.0f);
    CHECK(f[3] == 0.5f);
}
