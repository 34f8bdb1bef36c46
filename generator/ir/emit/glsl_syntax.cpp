#include <cmath>

#include <fmt/format.h>

#include "shader_syntax.h"

#include "watergen/ir/core/op_table.h"

namespace watergen {

std::string GlslSyntax::type(Type t) const {
    return type_name(t);
}

std::string GlslSyntax::temp_type(Type t, bool relaxed) const {
    return (relaxed && t != Type::Bool ? "mediump " : "") + type(t);
}

std::string GlslSyntax::half_type(Type t) const {
    switch (t) {
    case Type::Float:
        return "float16_t";
    case Type::Vec2:
        return "f16vec2";
    case Type::Vec3:
        return "f16vec3";
    case Type::Vec4:
        return "f16vec4";
    case Type::Mat3:
        return "f16mat3";
    default:
        return type(t);
    }
}

std::string GlslSyntax::convert(Type t, bool to_half, const std::string& expr) const {
    return (to_half ? half_type(t) : type(t)) + "(" + expr + ")";
}

std::vector<std::string> GlslSyntax::extensions(bool strict_half, bool loops) const {
    std::vector<std::string> lines;
    if (strict_half)
        lines.push_back("#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require");
    if (loops) lines.push_back("#extension GL_EXT_control_flow_attributes : require");
    return lines;
}

std::string GlslSyntax::loop_header(const std::string& index, int trip_count,
                                    UnrollHint unroll) const {
    static const char* const kAttribute[] = {"[[dont_unroll]] ", "[[unroll]] ", ""};
    return fmt::format("{}for (int {} = 0; {} < {}; ++{}) {{", kAttribute[int(unroll)], index,
                       index, trip_count, index);
}

std::string GlslSyntax::literal(double v) const {
    const float f = static_cast<float>(v);
    if (std::isnan(f)) return "uintBitsToFloat(0x7fc00000u)";
    if (std::isinf(f))
        return f > 0 ? "uintBitsToFloat(0x7f800000u)" : "uintBitsToFloat(0xff800000u)";
    // Shortest text that reads back as the same float: output is exact and stable.
    std::string s = fmt::format("{}", f);
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return f < 0 ? "(" + s + ")" : s;
}

std::string GlslSyntax::constant(const Node& n) const {
    if (n.values.size() == 1) return literal(n.values[0]);
    bool all_same = true;
    for (double v : n.values)
        all_same = all_same && v == n.values[0];
    if (all_same) return type(n.type) + "(" + literal(n.values[0]) + ")";
    std::vector<std::string> parts;
    for (double v : n.values)
        parts.push_back(literal(v));
    return construct(n.type, parts);
}

std::string GlslSyntax::uniform_ref(const std::string& name) const {
    return "params." + name;
}

std::string GlslSyntax::splat(Type t, const std::string& scalar, bool half) const {
    return (half ? half_type(t) : type(t)) + "(" + scalar + ")";
}

std::string GlslSyntax::construct(Type t, const std::vector<std::string>& args, bool half) const {
    return (half ? half_type(t) : type(t)) + "(" + fmt::format("{}", fmt::join(args, ", ")) + ")";
}

std::string GlslSyntax::call(Op op, Type result, const std::vector<std::string>& a,
                             const std::vector<Type>& arg_types, bool half) const {
    auto fn = [&](const char* name) {
        return std::string(name) + "(" + fmt::format("{}", fmt::join(a, ", ")) + ")";
    };
    switch (op) {
    case Op::Saturate:
        if (half) return "clamp(" + a[0] + ", float16_t(0.0), float16_t(1.0))";
        return "clamp(" + a[0] + ", 0.0, 1.0)";
    case Op::MatMulVec:
        return "(" + a[0] + " * " + a[1] + ")";
    case Op::Sample:
    case Op::SampleLevel: {
        const std::string sampler =
            (arg_types[0] == Type::TextureCube ? "samplerCube(" : "sampler2D(") + a[0] +
            ", linear_clamp)";
        if (op == Op::Sample) return "texture(" + sampler + ", " + a[1] + ")";
        return "textureLod(" + sampler + ", " + a[1] + ", " + a[2] + ")";
    }
    default:
        break;
    }
    (void)result;
    const OpInfo& info = op_info(op);
    return fn(info.glsl ? info.glsl : info.name);
}

std::vector<std::string> GlslSyntax::declarations(const ShaderInterface& in) const {
    std::vector<std::string> lines;
    if (const ResourceSlot* block = in.slot(kParamsResource);
        block && !in.uniforms.members.empty()) {
        // std140 on the push constant too (glslang's default there is std430): the block keeps
        // the uniform block's offsets, which the HLSL cbuffer's packoffsets match.
        lines.push_back(block->kind == ResourceKind::PushConstant
                            ? std::string("layout(push_constant, std140) uniform WaterParams {")
                            : fmt::format("layout(set = {}, binding = {}, std140) uniform "
                                          "WaterParams {{",
                                          block->set, block->binding));
        for (const auto& m : in.uniforms.members)
            lines.push_back(fmt::format("    layout(offset = {}) {} {}{};", m.offset, type(m.type),
                                        m.name, array_suffix(m)));
        lines.push_back("} params;");
    }
    const std::vector<std::string> constants = specialization_declarations(in);
    lines.insert(lines.end(), constants.begin(), constants.end());
    if (const ResourceSlot* sampler = in.slot(kSamplerResource))
        lines.push_back(fmt::format("layout(set = {}, binding = {}) uniform sampler linear_clamp;",
                                    sampler->set, sampler->binding));
    for (const auto& t : in.textures)
        lines.push_back(
            fmt::format("layout(set = {}, binding = {}) uniform {} {};", t.set, t.binding,
                        t.type == Type::TextureCube ? "textureCube" : "texture2D", t.name));
    for (size_t i = 0; i < in.varyings.size(); ++i)
        lines.push_back(fmt::format("layout(location = {}) in {} {};", i,
                                    type(in.varyings[i].second), in.varyings[i].first));
    return lines;
}

std::vector<std::string> GlslSyntax::specialization_declarations(const ShaderInterface& in) const {
    std::vector<std::string> lines;
    for (const auto& slot : in.specialization)
        lines.push_back(fmt::format("{} const float {} = {};", constant_id_attribute(slot.id),
                                    slot.name, literal(slot.default_value)));
    for (const auto& p : in.parameters) {
        if (!p.specialization || !is_vector(p.type)) continue;
        std::vector<std::string> components;
        for (const auto& slot : in.specialization)
            if (slot.parameter == p.name) components.push_back(slot.name);
        lines.push_back(specialization_vector(p.type, p.name, components));
    }
    return lines;
}

std::string GlslSyntax::constant_id_attribute(uint32_t id) const {
    return fmt::format("layout(constant_id = {})", id);
}

// A constant constructor of specialization constants is itself one (OpSpecConstantComposite).
std::string GlslSyntax::specialization_vector(Type t, const std::string& name,
                                              const std::vector<std::string>& components) const {
    return fmt::format("const {} {} = {};", type(t), name, construct(t, components));
}

std::vector<std::string> GlslSyntax::prelude(const std::set<Op>&, bool) const {
    return {};
}

std::vector<std::string>
GlslSyntax::quad_difference_helpers(const std::set<std::string>& types) const {
    std::vector<std::string> lines = {
        "// ddx / ddy of a fragment quad: tuples 4k..4k+3 are the pixels (0,0), (1,0), (0,1), "
        "(1,1), as",
        "// the CPU evaluator's lanes; axis 1 = x, 2 = y. Each lane's value goes through shared "
        "memory.",
    };
    for (const std::string& ty : types) {
        const std::string array = "probe_quad_" + ty;
        lines.push_back(
            fmt::format("{} {} {}[{}];", workgroup_shared(), ty, array, kProbeWorkgroupSize));
        lines.push_back(
            fmt::format("{} probe_quad_difference({} v, uint lane, uint axis) {{", ty, ty));
        lines.push_back(fmt::format("    {}[lane] = v;", array));
        lines.push_back(fmt::format("    {};", workgroup_barrier()));
        lines.push_back("    uint lo = lane & ~axis;");
        lines.push_back(fmt::format("    {} d = {}[lo | axis] - {}[lo];", ty, array, array));
        lines.push_back(fmt::format("    {}; // every lane has read before the next call writes",
                                    workgroup_barrier()));
        lines.push_back("    return d;");
        lines.push_back("}");
    }
    return lines;
}

} // namespace watergen
