// The kernels a compiled program's instructions run (block_program.h): what each IR operation
// computes over a block of lanes. Private to ir/.
//
// Every value is computed as the double-precision evaluator always computed it and rounded
// once as it is stored; float storage is that rounding to binary32. Where a float computation
// gives the same binary32 result (+ - * / of binary32 values: binary64 has more than 2 * 24 + 2
// bits, so rounding to it first changes nothing; comparisons, min, max, select, negation,
// which are exact), float-storage kernels compute in float, four lanes to a vector register.
//
// Half mode: a relaxed node's composite built-ins (dot, normalize, mix, pow, ...) round each
// intermediate to binary16 in the order lavapipe's lowering uses ("stepwise", measured per
// operation by tests/render/strict_half_ops_test.cpp); a node's result is rounded to binary16
// after the kernel (Rounding in block_program.h).
#pragma once

#include "block_program.h"

namespace watergen {

// An intermediate of a composite built-in: rounded to binary16 in the stepwise half form,
// as it is.
template <bool Stepwise> double half_step(double v) {
    if constexpr (Stepwise)
        return round_to_half(v);
    else
        return v;
}

// The kernel of an operation, for arguments 0 and 1 that vary per lane (lane step 1) or not
// (0), or nullptr (Loop, shape operations: see block_program.cpp).
Kernel op_kernel(Op op, bool wide, bool stepwise, uint32_t lane_step0, uint32_t lane_step1);
// The kernels op_kernel() leaves to block_kernels_data.cpp: leaves, texture sampling,
// derivatives and the composite built-ins.
Kernel data_kernel(Op op, bool wide, bool stepwise, uint32_t lane_step0, uint32_t lane_step1);

// Float storage: sin and cos of one scalar argument, rows 0 and 1 of the result, as
// float(std::sin(double(x))) and float(std::cos(double(x))) (block_kernels_trig.cpp).
Kernel sincos_kernel(uint32_t lane_step);

// Copies component c from Program::gathers[aux + c] (Construct, Swizzle, Splat, ...).
Kernel copy_kernel(bool wide);
// Argument 0 rounded to binary16: a relaxed node's 32-bit argument in half mode (toward zero
// for a texture sample, as lavapipe converts one).
Kernel narrow_kernel(bool toward_zero);
// Rounds an instruction's float-stored result on to binary16 (Instr::round).
void round_result(const Instr& ins, Exec& ex, size_t lanes);

} // namespace watergen
