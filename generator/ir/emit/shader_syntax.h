// How one language spells the IR. GlslSyntax is the base; HlslSyntax overrides what differs.
#pragma once

#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "watergen/ir/emit/emitter.h"

namespace watergen {

// "[N]" after an array member's name, "" for other members.
inline std::string array_suffix(const UniformSlot& m) {
    return m.array_size ? fmt::format("[{}]", m.array_size) : std::string();
}

class GlslSyntax {
  public:
    virtual ~GlslSyntax() = default;
    virtual std::string type(Type t) const;
    virtual std::string literal(double v) const;
    // Declared type of a temporary; relaxed ones are mediump / min16float.
    virtual std::string temp_type(Type t, bool relaxed) const;
    // Explicit binary16 spelling of a float type (strict half): float16_t, f16vec3, f16mat3.
    virtual std::string half_type(Type t) const;
    // `expr` converted to `t` at 16 bits (to_half) or 32 bits: the only place where the two
    // widths meet in a strict-half shader, so every conversion is visible in the source.
    virtual std::string convert(Type t, bool to_half, const std::string& expr) const;
    // Lines after the version line: the float16 extension of a strict-half GLSL shader, the
    // control-flow attributes of one with loops.
    virtual std::vector<std::string> extensions(bool strict_half, bool loops) const;
    // `for (int index = 0; index < trip_count; ++index) {` with the unroll hint.
    virtual std::string loop_header(const std::string& index, int trip_count,
                                    UnrollHint unroll) const;
    // An int variable as a float.
    virtual std::string int_to_float(const std::string& name) const {
        return "float(" + name + ")";
    }
    // A float truncated to an int.
    virtual std::string float_to_int(const std::string& expr) const { return "int(" + expr + ")"; }
    virtual std::string constant(const Node& n) const;
    virtual std::string uniform_ref(const std::string& name) const;
    // `half`: the result is a binary16 type (strict half), and so are the arguments.
    virtual std::string splat(Type t, const std::string& scalar, bool half = false) const;
    virtual std::string construct(Type t, const std::vector<std::string>& args,
                                  bool half = false) const;
    // Intrinsic calls, texture sampling and matrix products; arguments already spelled.
    virtual std::string call(Op op, Type result, const std::vector<std::string>& args,
                             const std::vector<Type>& arg_types, bool half = false) const;
    virtual std::vector<std::string> declarations(const ShaderInterface& in) const;
    // The specialization constants of `in` (one float per slot), then each vector parameter
    // composed from its components under the parameter's name.
    std::vector<std::string> specialization_declarations(const ShaderInterface& in) const;
    virtual std::string constant_id_attribute(uint32_t id) const;
    virtual std::string specialization_vector(Type t, const std::string& name,
                                              const std::vector<std::string>& components) const;
    // Helper functions the body calls; `strict_half` adds their binary16 overloads.
    virtual std::vector<std::string> prelude(const std::set<Op>& used,
                                             bool strict_half = false) const;
    virtual std::string entry_inputs(const ShaderInterface&) const { return ""; }
    virtual std::string comment(const std::string& text) const { return "// " + text; }
    // Probe (compute) stand-in for ddx / ddy, which only fragment stages have: functions
    // probe_quad_difference(v, lane, axis) for each spelled type in `types` (see emit_probe).
    std::vector<std::string> quad_difference_helpers(const std::set<std::string>& types) const;
    virtual std::string workgroup_shared() const { return "shared"; }
    virtual std::string workgroup_barrier() const { return "barrier()"; }
};

class HlslSyntax final : public GlslSyntax {
  public:
    std::string type(Type t) const override;
    std::string constant(const Node& n) const override;
    std::string temp_type(Type t, bool relaxed) const override;
    std::string half_type(Type t) const override;
    std::string convert(Type t, bool to_half, const std::string& expr) const override;
    std::vector<std::string> extensions(bool, bool) const override { return {}; }
    std::string loop_header(const std::string& index, int trip_count,
                            UnrollHint unroll) const override;
    std::string int_to_float(const std::string& name) const override {
        return "((float)" + name + ")";
    }
    std::string float_to_int(const std::string& expr) const override {
        return "((int)" + expr + ")";
    }
    std::string uniform_ref(const std::string& name) const override;
    std::string splat(Type t, const std::string& scalar, bool half = false) const override;
    std::string construct(Type t, const std::vector<std::string>& args,
                          bool half = false) const override;
    std::string call(Op op, Type result, const std::vector<std::string>& args,
                     const std::vector<Type>& arg_types, bool half = false) const override;
    std::vector<std::string> declarations(const ShaderInterface& in) const override;
    std::string constant_id_attribute(uint32_t id) const override;
    std::string specialization_vector(Type t, const std::string& name,
                                      const std::vector<std::string>& components) const override;
    std::vector<std::string> prelude(const std::set<Op>& used,
                                     bool strict_half = false) const override;
    std::string entry_inputs(const ShaderInterface& in) const override;
    std::string workgroup_shared() const override { return "groupshared"; }
    std::string workgroup_barrier() const override { return "GroupMemoryBarrierWithGroupSync()"; }
};

} // namespace watergen
