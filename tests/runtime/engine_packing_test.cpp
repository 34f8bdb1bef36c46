// Uniform packing against the reflection of both languages, for every variant of the default
// material (its unpruned build) and for every variant of the example scenes: every parameter set
// to values of its own, then every reflected member's bytes read back at its reflected offset,
// element stride and size; the bytes no member covers stay zero; and the reflected offset is
// where the generator placed the parameter (std140 and cbuffer agree).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>

#include "engine_builds.h"
#include "watergen/runtime/uniform_writer.h"

using namespace watergen;

namespace {

struct Counts {
    size_t variants = 0, blocks = 0, members = 0, floats = 0;
};

// A value no other float of the block has, inside the parameter's range (the writer refuses
// others): a point of [min, max] set by the parameter index, element and component. Blocks have
// fewer than 64 parameters of at most 64 floats each, so the 4096 points are distinct floats for
// every range wider than 1e-3 relative to its bounds.
float marker(const BlockParameter& param, size_t parameter, size_t i) {
    const double k = double(parameter * 64 + i + 1) / 4097.0;
    return float(param.min + (param.max - param.min) * k);
}

void check_variant(const ShaderBuild& b, const BuildVariant& v, Counts& n) {
    UniformWriter w(v);
    for (size_t p = 0; p < v.parameters.size(); ++p) {
        const BlockParameter& param = v.parameters[p];
        if (w.computed(param.name)) continue; // pack() computes it (host_values.h)
        std::vector<float> values(type_components(param.type) *
                                  std::max<uint32_t>(param.array_size, 1));
        for (size_t i = 0; i < values.size(); ++i)
            values[i] = marker(param, p, i);
        const Write r = w.set(param.name, values);
        INFO(v.key << " " << param.name << ": " << r.error);
        REQUIRE(r.ok);
    }
    ++n.variants;
    for (const char* lang : {"glsl", "hlsl"}) {
        std::string error;
        const auto refl = b.reflection(v, lang, ShaderStage::Fragment, &error);
        INFO(v.key << " " << lang << ": " << error);
        REQUIRE(refl);
        const auto bytes = w.pack(*refl, &error);
        REQUIRE(bytes);
        const DescriptorBinding* block = nullptr;
        for (const auto& binding : refl->bindings)
            if (binding.kind == DescriptorKind::UniformBuffer) block = &binding;
        REQUIRE(block);
        ++n.blocks;
        CHECK(bytes->size() == (block->block_size + 15) / 16 * 16);
        std::vector<bool> covered(bytes->size(), false);
        for (const UniformMember& m : block->members) {
            size_t p = 0;
            while (p < v.parameters.size() && v.parameters[p].name != m.name)
                ++p;
            REQUIRE(p < v.parameters.size());
            const BlockParameter& param = v.parameters[p];
            INFO(m.name << " (" << m.type << ") at " << m.offset);
            CHECK(m.offset == param.offset);
            const uint32_t comps = type_components(param.type);
            const uint32_t count = std::max<uint32_t>(m.array_size, 1);
            const uint32_t stride = m.array_size ? m.array_stride : comps * 4;
            CHECK(m.size == (m.array_size ? count * stride : comps * 4));
            ++n.members;
            for (uint32_t e = 0; e < count; ++e)
                for (uint32_t c = 0; c < comps; ++c) {
                    const size_t at = m.offset + size_t(e) * stride + c * 4;
                    REQUIRE(at + 4 <= bytes->size());
                    float f = 0;
                    std::memcpy(&f, bytes->data() + at, 4);
                    // A host rule's member is what the rule makes of the markers
                    // (host_values_test holds the rules); the others are the markers.
                    if (param.host.rule == HostRule::Given)
                        CHECK(f == marker(param, p, size_t(e) * comps + c));
                    else
                        CHECK(std::isfinite(f));
                    for (size_t k = 0; k < 4; ++k)
                        covered[at + k] = true;
                    ++n.floats;
                }
        }
        for (size_t i = 0; i < bytes->size(); ++i)
            if (!covered[i]) CHECK(int((*bytes)[i]) == 0);
    }
}

} // namespace

TEST_CASE("every variant of the default material packs to the reflected std140 and cbuffer "
          "layouts") {
    const ShaderBuild b = test::open_example_build(false);
    REQUIRE(b.variants().size() == 144);
    Counts n;
    for (const BuildVariant& v : b.variants())
        check_variant(b, v, n);
    WARN("packing checked: " << n.variants << " variants, " << n.blocks << " blocks (GLSL std140 "
                             << "+ HLSL cbuffer), " << n.members << " members, " << n.floats
                             << " floats");
    CHECK(n.variants == 144);
    CHECK(n.blocks == 288);
}

TEST_CASE("the example scenes' variants pack to their reflected layouts, folded parameters "
          "absent") {
    const ShaderBuild b = test::open_example_build(true);
    Counts n;
    for (const BuildVariant& v : b.variants()) {
        if (!v.files.count("hlsl")) continue; // mountain_lake builds GLSL, ESSL and MSL only
        check_variant(b, v, n);
        for (const auto& [name, value] : v.folded_parameters)
            CHECK_FALSE(UniformWriter(v).has(name));
    }
    WARN("packing checked (scenes): " << n.variants << " variants, " << n.blocks << " blocks, "
                                      << n.members << " members, " << n.floats << " floats");
    CHECK(n.variants == 32);
}
