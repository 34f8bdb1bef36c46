// What each room asks of an operation, in one row per Op (op_table.cpp): its name and arity, how
// the DSL types it, how the back ends spell a call to it, and the properties the CPU evaluator,
// the float error model and the fold pass read. A new op is one row here; the rooms that give it
// meaning (a CPU kernel, an interval rule, a spelling that is not a call) say so where they
// switch on what the row cannot hold.
#pragma once

#include "watergen/ir/core/ir.h"

#include <cstdint>

namespace watergen {

// Where an operation's value comes from.
enum class OpKind : uint8_t {
    Input,      // Constant, Uniform, Varying, Texture: the graph's leaves
    BodyInput,  // LoopIndex, Carried, Captured: the leaves of a loop body or switch case
    Math,       // a function of its operands' values alone: arithmetic, logic, shape, intrinsics
    Element,    // UniformElement: an array parameter's element at an index
    Sampling,   // Sample, SampleLevel: a texture read at a coordinate
    Derivative, // Ddx, Ddy: the difference to the neighbouring pixel
    Control,    // Loop, LoopResult, Switch, SwitchResult: bodies of their own
};

// How make() types an operation from its operands (dsl.cpp's infer).
enum class OpTyping : uint8_t {
    NotMade,     // built by its own DSL function, not make(): leaves, shape, control
    Arithmetic,  // + - * /: equal types, a float scalar against a vector, ints, Mat3 * Vec3
    FloatUnary,  // a float scalar or vector in, the same out (negation takes ints too)
    Compare,     // two scalars of one type, a bool out
    Logic,       // two bools
    LogicNot,    // one bool
    Select,      // a bool, then two values of one type
    Dot,         // two float vectors of one size, a float out
    Length,      // a float vector, a float out
    Cross,       // two vec3
    Reflect,     // two float vectors of one size
    Refract,     // vecN incident, vecN normal, float eta
    SameFloat,   // every operand the same float type, which is the result's
    Sample,      // (texture2D, vec2) or (textureCube, vec3), a vec4 out
    SampleLevel, // the same and a float level
    Construct,   // float scalars and vectors making 2 to 4 components
};

struct OpInfo {
    Op op;
    const char* name; // in diagnostics; the GLSL and HLSL call unless glsl or hlsl says otherwise
    int8_t arity;     // operands make() takes; -1: any number (Construct) or not made
    OpKind kind;
    OpTyping typing;
    bool infix;     // written between its two operands: + - * / comparisons && ||
    bool broadcast; // componentwise, a float scalar operand splat to the vectors' size by make()
    // The float error model: the binary32 result is the correctly rounded exact one on every
    // GPU, so two float evaluations agree (float_error.h, block_program.cpp).
    bool exact_in_binary32;
    const char* glsl; // the GLSL call's name where it is not `name`; nullptr otherwise
    const char* hlsl; // the HLSL call's name where it is not the GLSL one; nullptr otherwise
};

const OpInfo& op_info(Op op);

// Every row, in the enum's order.
const OpInfo* op_table_begin();
const OpInfo* op_table_end();

} // namespace watergen
