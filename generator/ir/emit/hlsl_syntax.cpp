#include <fmt/format.h>

#include "shader_syntax.h"

#include "watergen/ir/core/op_table.h"

namespace watergen {

std::string HlslSyntax::type(Type t) const {
    switch (t) {
    case Type::Vec2:
        return "float2";
    case Type::Vec3:
        return "float3";
    case Type::Vec4:
        return "float4";
    case Type::Mat3:
        return "float3x3";
    case Type::Texture2D:
        return "Texture2D";
    case Type::TextureCube:
        return "TextureCube";
    default:
        return GlslSyntax::type(t);
    }
}

std::string HlslSyntax::constant(const Node& n) const {
    if (n.values.size() == 1) return literal(n.values[0]);
    std::vector<std::string> parts;
    for (double v : n.values)
        parts.push_back(literal(v));
    return construct(n.type, parts);
}

std::string HlslSyntax::temp_type(Type t, bool relaxed) const {
    return (relaxed && (is_float_numeric(t) || t == Type::Mat3) ? "min16" : "") + type(t);
}

std::string HlslSyntax::half_type(Type t) const {
    switch (t) {
    case Type::Float:
        return "half";
    case Type::Vec2:
        return "half2";
    case Type::Vec3:
        return "half3";
    case Type::Vec4:
        return "half4";
    case Type::Mat3:
        return "half3x3";
    default:
        return type(t);
    }
}

std::string HlslSyntax::convert(Type t, bool to_half, const std::string& expr) const {
    return "((" + (to_half ? half_type(t) : type(t)) + ")(" + expr + "))";
}

std::string HlslSyntax::loop_header(const std::string& index, int trip_count,
                                    UnrollHint unroll) const {
    static const char* const kAttribute[] = {"[loop] ", "[unroll] ", ""};
    return fmt::format("{}for (int {} = 0; {} < {}; ++{}) {{", kAttribute[int(unroll)], index,
                       index, trip_count, index);
}

// cbuffer members are globals in HLSL.
std::string HlslSyntax::uniform_ref(const std::string& name) const {
    return name;
}

std::string HlslSyntax::splat(Type t, const std::string& scalar, bool half) const {
    return convert(t, half, scalar);
}

// float3x3(c0, c1, c2) takes rows, so the GLSL columns become HLSL rows and products are
// written mul(v, M): both compute c0 * v.x + c1 * v.y + c2 * v.z.
std::string HlslSyntax::construct(Type t, const std::vector<std::string>& args, bool half) const {
    return GlslSyntax::construct(t, args, half);
}

std::string HlslSyntax::call(Op op, Type result, const std::vector<std::string>& a,
                             const std::vector<Type>& arg_types, bool half) const {
    if (half) {
        // glslang 12's HLSL front end has no 16-bit overloads of the intrinsics: a call with
        // half arguments resolves to the float one (arguments widened exactly), so it runs at
        // 32 bits and its result is rounded to half here; mul() has no half3x3 overload at all.
        // Arithmetic and wg_mod stay 16-bit.
        if (op == Op::MatMulVec)
            return convert(result, true,
                           "mul(" + convert(Type::Vec3, false, a[1]) + ", " +
                               convert(Type::Mat3, false, a[0]) + ")");
        return convert(result, true, call(op, result, a, arg_types, false));
    }
    auto fn = [&](const char* name) {
        return std::string(name) + "(" + fmt::format("{}", fmt::join(a, ", ")) + ")";
    };
    if (const char* name = op_info(op).hlsl) return fn(name);
    switch (op) {
    case Op::MatMulVec:
        return "mul(" + a[1] + ", " + a[0] + ")";
    case Op::Sample:
        return a[0] + ".Sample(linear_clamp, " + a[1] + ")";
    case Op::SampleLevel:
        return a[0] + ".SampleLevel(linear_clamp, " + a[1] + ", " + a[2] + ")";
    default:
        return GlslSyntax::call(op, result, a, arg_types, half);
    }
}

std::vector<std::string> HlslSyntax::declarations(const ShaderInterface& in) const {
    std::vector<std::string> lines;
    if (const ResourceSlot* block = in.slot(kParamsResource);
        block && !in.uniforms.members.empty()) {
        // No register on a push constant: glslang 12 would decorate it with a DescriptorSet,
        // which spirv-val rejects (VUID-StandaloneSpirv-DescriptorSet-06491).
        lines.push_back(
            block->kind == ResourceKind::PushConstant
                ? std::string("[[vk::push_constant]] cbuffer WaterParams {")
                : fmt::format(
                      "[[vk::binding({}, {})]] cbuffer WaterParams : register(b{}, space{}) {{",
                      block->binding, block->set, block->hlsl_register, block->hlsl_space));
        for (const auto& m : in.uniforms.members) {
            const char component = "xyzw"[(m.offset % 16) / 4];
            lines.push_back(fmt::format("    {} {}{} : packoffset(c{}.{});", type(m.type), m.name,
                                        array_suffix(m), m.offset / 16, component));
        }
        lines.push_back("};");
    }
    const std::vector<std::string> constants = specialization_declarations(in);
    lines.insert(lines.end(), constants.begin(), constants.end());
    if (const ResourceSlot* sampler = in.slot(kSamplerResource))
        lines.push_back(fmt::format(
            "[[vk::binding({}, {})]] SamplerState linear_clamp : register(s{}, space{});",
            sampler->binding, sampler->set, sampler->hlsl_register, sampler->hlsl_space));
    for (const auto& t : in.textures) {
        const ResourceSlot* s = in.slot(t.name);
        lines.push_back(fmt::format("[[vk::binding({}, {})]] {} {} : register(t{}, space{});",
                                    t.binding, t.set, type(t.type), t.name, s->hlsl_register,
                                    s->hlsl_space));
    }
    return lines;
}

std::string HlslSyntax::constant_id_attribute(uint32_t id) const {
    return fmt::format("[[vk::constant_id({})]]", id);
}

// glslang 12 rejects a constructor of specialization constants as a const initializer
// ("non-matching or non-convertible constant type"); an initializer list is accepted and
// composes the vector where it is read.
std::string HlslSyntax::specialization_vector(Type t, const std::string& name,
                                              const std::vector<std::string>& components) const {
    return fmt::format("static const {} {} = {{{}}};", type(t), name, fmt::join(components, ", "));
}

std::vector<std::string> HlslSyntax::prelude(const std::set<Op>& used, bool strict_half) const {
    if (!used.count(Op::Mod)) return {};
    std::vector<std::string> lines = {"// GLSL mod(): x - y * floor(x / y)"};
    for (Type t : {Type::Float, Type::Vec2, Type::Vec3, Type::Vec4})
        for (bool half : {false, true})
            if (!half || strict_half)
                lines.push_back(
                    half
                        ? fmt::format("{0} wg_mod({0} x, {0} y) {{ return x - y * ({0})(floor(x "
                                      "/ y)); }}",
                                      half_type(t))
                        : fmt::format("{0} wg_mod({0} x, {0} y) {{ return x - y * floor(x / y); }}",
                                      type(t)));
    return lines;
}

std::string HlslSyntax::entry_inputs(const ShaderInterface& in) const {
    std::vector<std::string> params;
    for (size_t i = 0; i < in.varyings.size(); ++i)
        params.push_back(fmt::format("{} {} : TEXCOORD{}", type(in.varyings[i].second),
                                     in.varyings[i].first, i));
    return fmt::format("{}", fmt::join(params, ", "));
}

} // namespace watergen
