// One row per Op (op_table.h), in the enum's order: the compiler checks the order below.
#include "watergen/ir/core/op_table.h"

#include <cstddef>
#include <iterator>

namespace watergen {

namespace {

using K = OpKind;
using T = OpTyping;

constexpr bool infix = true, broadcast = true, exact = true;

// Columns: op, name, arity, kind, typing, infix, broadcast, exact_in_binary32, glsl, hlsl.
constexpr OpInfo kOps[] = {
    {Op::Constant, "constant", 0, K::Input, T::NotMade, false, false, exact, nullptr, nullptr},
    {Op::Uniform, "uniform", 0, K::Input, T::NotMade, false, false, exact, nullptr, nullptr},
    {Op::Varying, "varying", 0, K::Input, T::NotMade, false, false, false, nullptr, nullptr},
    {Op::Texture, "texture", 0, K::Input, T::NotMade, false, false, false, nullptr, nullptr},
    {Op::Add, "+", 2, K::Math, T::Arithmetic, infix, false, exact, nullptr, nullptr},
    {Op::Sub, "-", 2, K::Math, T::Arithmetic, infix, false, exact, nullptr, nullptr},
    // A GPU may fuse a product into the add that follows; a quotient may be a reciprocal.
    {Op::Mul, "*", 2, K::Math, T::Arithmetic, infix, false, false, nullptr, nullptr},
    {Op::Div, "/", 2, K::Math, T::Arithmetic, infix, false, false, nullptr, nullptr},
    {Op::Neg, "negate", 1, K::Math, T::FloatUnary, false, false, exact, nullptr, nullptr},
    {Op::Less, "<", 2, K::Math, T::Compare, infix, false, exact, nullptr, nullptr},
    {Op::LessEqual, "<=", 2, K::Math, T::Compare, infix, false, exact, nullptr, nullptr},
    {Op::Greater, ">", 2, K::Math, T::Compare, infix, false, exact, nullptr, nullptr},
    {Op::GreaterEqual, ">=", 2, K::Math, T::Compare, infix, false, exact, nullptr, nullptr},
    {Op::Equal, "==", 2, K::Math, T::Compare, infix, false, exact, nullptr, nullptr},
    {Op::NotEqual, "!=", 2, K::Math, T::Compare, infix, false, exact, nullptr, nullptr},
    {Op::And, "&&", 2, K::Math, T::Logic, infix, false, exact, nullptr, nullptr},
    {Op::Or, "||", 2, K::Math, T::Logic, infix, false, exact, nullptr, nullptr},
    {Op::Not, "!", 1, K::Math, T::LogicNot, false, false, exact, nullptr, nullptr},
    {Op::Select, "select", 3, K::Math, T::Select, false, broadcast, exact, nullptr, nullptr},
    {Op::Swizzle, "swizzle", 1, K::Math, T::NotMade, false, false, false, nullptr, nullptr},
    {Op::Construct, "construct", -1, K::Math, T::Construct, false, false, false, nullptr, nullptr},
    {Op::Splat, "splat", 1, K::Math, T::NotMade, false, false, false, nullptr, nullptr},
    {Op::Dot, "dot", 2, K::Math, T::Dot, false, false, false, nullptr, nullptr},
    {Op::Cross, "cross", 2, K::Math, T::Cross, false, false, false, nullptr, nullptr},
    {Op::Normalize, "normalize", 1, K::Math, T::FloatUnary, false, false, false, nullptr, nullptr},
    {Op::Length, "length", 1, K::Math, T::Length, false, false, false, nullptr, nullptr},
    {Op::Mix, "mix", 3, K::Math, T::SameFloat, false, broadcast, false, nullptr, "lerp"},
    {Op::Clamp, "clamp", 3, K::Math, T::SameFloat, false, broadcast, exact, nullptr, nullptr},
    {Op::Saturate, "saturate", 1, K::Math, T::FloatUnary, false, false, exact, nullptr, "saturate"},
    {Op::Pow, "pow", 2, K::Math, T::SameFloat, false, broadcast, false, nullptr, nullptr},
    {Op::Exp, "exp", 1, K::Math, T::FloatUnary, false, false, false, nullptr, nullptr},
    {Op::Exp2, "exp2", 1, K::Math, T::FloatUnary, false, false, false, nullptr, nullptr},
    {Op::Log, "log", 1, K::Math, T::FloatUnary, false, false, false, nullptr, nullptr},
    {Op::Sqrt, "sqrt", 1, K::Math, T::FloatUnary, false, false, false, nullptr, nullptr},
    {Op::Rsqrt, "rsqrt", 1, K::Math, T::FloatUnary, false, false, false, "inversesqrt", "rsqrt"},
    {Op::Abs, "abs", 1, K::Math, T::FloatUnary, false, false, exact, nullptr, nullptr},
    {Op::Sign, "sign", 1, K::Math, T::FloatUnary, false, false, exact, nullptr, nullptr},
    {Op::Min, "min", 2, K::Math, T::SameFloat, false, broadcast, exact, nullptr, nullptr},
    {Op::Max, "max", 2, K::Math, T::SameFloat, false, broadcast, exact, nullptr, nullptr},
    {Op::Sin, "sin", 1, K::Math, T::FloatUnary, false, false, false, nullptr, nullptr},
    {Op::Cos, "cos", 1, K::Math, T::FloatUnary, false, false, false, nullptr, nullptr},
    {Op::Atan2, "atan2", 2, K::Math, T::SameFloat, false, broadcast, false, "atan", "atan2"},
    {Op::Reflect, "reflect", 2, K::Math, T::Reflect, false, false, false, nullptr, nullptr},
    {Op::Refract, "refract", 3, K::Math, T::Refract, false, false, false, nullptr, nullptr},
    {Op::Step, "step", 2, K::Math, T::SameFloat, false, broadcast, exact, nullptr, nullptr},
    {Op::Smoothstep, "smoothstep", 3, K::Math, T::SameFloat, false, broadcast, false, nullptr,
     nullptr},
    {Op::Fract, "fract", 1, K::Math, T::FloatUnary, false, false, exact, nullptr, "frac"},
    {Op::Floor, "floor", 1, K::Math, T::FloatUnary, false, false, exact, nullptr, nullptr},
    // GLSL's mod floors; HLSL's fmod truncates, so HLSL calls the prelude's wg_mod.
    {Op::Mod, "mod", 2, K::Math, T::SameFloat, false, broadcast, false, nullptr, "wg_mod"},
    // make(Op::Mul, {Mat3, Vec3}) makes it.
    {Op::MatMulVec, "matrix * vector", 2, K::Math, T::NotMade, false, false, false, nullptr,
     nullptr},
    {Op::Sample, "sample", 2, K::Sampling, T::Sample, false, false, false, nullptr, nullptr},
    {Op::SampleLevel, "sampleLevel", 3, K::Sampling, T::SampleLevel, false, false, false, nullptr,
     nullptr},
    // Exact in binary32: a difference of two values, rounded to nearest.
    {Op::Ddx, "ddx", 1, K::Derivative, T::FloatUnary, false, false, exact, "dFdx", "ddx"},
    {Op::Ddy, "ddy", 1, K::Derivative, T::FloatUnary, false, false, exact, "dFdy", "ddy"},
    {Op::Loop, "loop", -1, K::Control, T::NotMade, false, false, false, nullptr, nullptr},
    {Op::LoopResult, "loop result", 1, K::Control, T::NotMade, false, false, false, nullptr,
     nullptr},
    {Op::LoopIndex, "loop index", 0, K::BodyInput, T::NotMade, false, false, exact, nullptr,
     nullptr},
    {Op::Carried, "carried", 0, K::BodyInput, T::NotMade, false, false, false, nullptr, nullptr},
    {Op::Captured, "captured", 0, K::BodyInput, T::NotMade, false, false, false, nullptr, nullptr},
    {Op::UniformElement, "element", 1, K::Element, T::NotMade, false, false, exact, nullptr,
     nullptr},
    {Op::Switch, "switch", -1, K::Control, T::NotMade, false, false, false, nullptr, nullptr},
    {Op::SwitchResult, "switch result", 1, K::Control, T::NotMade, false, false, false, nullptr,
     nullptr},
};

constexpr bool in_enum_order() {
    for (size_t i = 0; i < std::size(kOps); ++i)
        if (static_cast<size_t>(kOps[i].op) != i) return false;
    return true;
}
static_assert(in_enum_order(), "op_table.cpp: a row out of the enum's order");
static_assert(std::size(kOps) == static_cast<size_t>(kLastOp) + 1,
              "op_table.cpp: an op without a row, or a row without an op");

} // namespace

const OpInfo& op_info(Op op) {
    return kOps[static_cast<size_t>(op)];
}

const OpInfo* op_table_begin() {
    return std::begin(kOps);
}

const OpInfo* op_table_end() {
    return std::end(kOps);
}

const char* op_name(Op op) {
    return op_info(op).name;
}

bool is_leaf(Op op) {
    const OpKind k = op_info(op).kind;
    return k == OpKind::Input || k == OpKind::BodyInput;
}

bool is_infix(Op op) {
    return op_info(op).infix;
}

} // namespace watergen
