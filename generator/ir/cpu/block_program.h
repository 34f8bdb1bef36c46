// The CPU evaluator's compiled form of a graph: a flat list of instructions, each an operation
// resolved once into a kernel (a function over a block of lanes) with its operands' places in
// an arena of values laid out structure-of-arrays (a component's lanes side by side). Private
// to ir/: block_program.cpp compiles, block_kernels*.cpp hold the kernels, block_evaluator.cpp
// runs a program over blocks.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "watergen/ir/core/shader_values.h"
#include "watergen/ir/cpu/cpu_evaluator.h"

namespace watergen {

constexpr size_t kBlock = 256; // lanes per block: a multiple of 4 (whole quads)

// Where a value lies in the arena: component c of lane l at offset + l * lane_step +
// c * comp_step. lane_step 0: the same on every lane; comp_step 0: one component for all.
struct Operand {
    uint32_t offset = 0;
    uint32_t lane_step = 0, comp_step = 0;
    uint32_t slot = UINT32_MAX; // compile time only: the storage it lies in (none: a texture)

    // Component c alone, as a scalar.
    Operand component(uint32_t c) const { return {offset + c * comp_step, lane_step, 0, slot}; }
};

struct Exec;
struct Instr;
// Computes one instruction over `lanes` lanes (the block's, or 1 for a lane-invariant value).
using Kernel = void (*)(const Instr&, Exec&, size_t lanes);

// Rounding after the kernel, beyond the storage's own: float storage rounds every value to
// binary32 as it is stored; the half mode's relaxed nodes round on to binary16.
enum class Rounding : uint8_t { None, Half, HalfTowardZero };

struct Instr {
    Kernel kernel = nullptr;
    Operand out;
    Operand args[3];
    uint32_t comps = 0;    // components written
    bool per_lane = false; // over the block's lanes, else one lane
    Rounding round = Rounding::None;
    const void* data = nullptr; // constants, parameter values, a varying, a texture
    uint32_t aux = 0;           // kernel-specific: a count, an index, a flag
    uint32_t site = UINT32_MAX; // double programs: Program::sites[site] computed it
    bool exact = false;         // the same in any binary32 evaluation (block_program.cpp)
};

// A loop: each carried value has a place of its own (`storage`; lane step 0 when it is the same
// on every lane, block_invariance.h), set from `initial`, then from `next` after each iteration.
struct LoopPlan {
    struct Carry {
        Operand storage, initial, next;
        uint32_t comps = 0;
    };
    std::vector<Instr> body; // run once per iteration
    std::vector<Carry> carried;
    Operand keep_going;
    bool has_exit = false;
    int trip_count = 0;   // the most iterations
    bool counted = false; // fewer from data: the value at `count` (LoopBody::counted)
    Operand count;
};

// A reason the evaluation fails: always, or (a varying of `size` values) from the block that
// reads past its end.
struct Check {
    std::string message;
    size_t varying_size = SIZE_MAX, varying_comps = 0;
};

struct Program {
    bool wide = false;                 // values stored as double (else float)
    std::vector<Instr> prologue, main; // once per thread; once per block
    std::vector<LoopPlan> loops;       // Instr::aux of a loop instruction
    std::vector<Operand> gathers;      // per component, the sources of copies
    std::vector<Check> checks;         // in node order
    size_t arena = 0;                  // values per evaluator
    Operand root;
    uint32_t root_comps = 0;
    std::vector<EvalSite> sites; // double programs: the operations that compute values
    // The values of parameters with a host rule (ir/core/shader_values.h), which the
    // instructions reading them point into (a map: its values never move).
    ParameterValues host;
};

// What a kernel sees: the arena, the block and the enclosing loops' iteration.
struct Exec {
    void* arena = nullptr;
    size_t begin = 0;      // first lane of the block
    size_t lanes = 0;      // lanes in the block
    double loop_index = 0; // of the innermost loop running
    const Program* program = nullptr;
    const EvalInputs* inputs = nullptr;
    const FloatPerturbation* perturbation = nullptr; // double programs, when active
};

// Compiles the nodes `root` depends on. Double precision stores doubles; float and half store
// floats (every value of theirs is a binary32 value).
Program compile_program(const Graph& g, uint32_t root, const EvalInputs& in, EvalPrecision p);

// Why the block of `count` lanes from `begin` cannot be evaluated; empty when it can.
std::string block_error(const Program& program, size_t begin, size_t count);

} // namespace watergen
