// BlockEvaluator: the run over a program's instructions, and loops.
#include "block_evaluator.h"

#include <algorithm>

#include "block_kernels.h"

namespace watergen {

namespace {

void run_list(const std::vector<Instr>& list, Exec& ex) {
    for (const Instr& ins : list) {
        const size_t lanes = ins.per_lane ? ex.lanes : 1;
        ins.kernel(ins, ex, lanes);
        if (ins.round != Rounding::None) round_result(ins, ex, lanes);
    }
}

template <class T> void run_loop(const Instr& ins, Exec& ex, size_t n) {
    const LoopPlan& loop = ex.program->loops[ins.aux];
    T* m = static_cast<T*>(ex.arena);
    auto row = [&](const Operand& o, uint32_t c) { return m + o.offset + c * o.comp_step; };
    for (const auto& k : loop.carried)
        for (uint32_t c = 0; c < k.comps; ++c) {
            const T* from = row(k.initial, c);
            T* to = row(k.storage, c);
            for (size_t l = 0; l < n; ++l)
                to[l] = from[l * k.initial.lane_step];
        }
    unsigned char active[kBlock];
    std::fill_n(active, n, 1);
    size_t remaining = n;
    const double outer_index = ex.loop_index;
    for (int i = 0; i < loop.trip_count && remaining > 0; ++i) {
        ex.loop_index = i;
        run_list(loop.body, ex);
        for (const auto& k : loop.carried)
            for (uint32_t c = 0; c < k.comps; ++c) {
                const T* __restrict from = row(k.next, c);
                T* __restrict to = row(k.storage, c);
                const size_t step = k.next.lane_step;
                if (remaining == n) {
                    for (size_t l = 0; l < n; ++l)
                        to[l] = from[l * step];
                } else {
                    for (size_t l = 0; l < n; ++l)
                        to[l] = active[l] ? from[l * step] : to[l];
                }
            }
        if (!loop.has_exit) continue;
        const T* go = m + loop.keep_going.offset;
        for (size_t l = 0; l < n; ++l)
            if (active[l] && go[l * loop.keep_going.lane_step] == 0) {
                active[l] = 0;
                --remaining;
            }
    }
    ex.loop_index = outer_index;
}

} // namespace

Kernel loop_kernel(bool wide) {
    return wide ? run_loop<double> : run_loop<float>;
}

BlockEvaluator::BlockEvaluator(const Program& program, const EvalInputs& in) : program_(program) {
    if (program.wide)
        wide_.assign(program.arena, 0.0);
    else
        narrow_.assign(program.arena, 0.0f);
    exec_.arena = program.wide ? static_cast<void*>(wide_.data()) : narrow_.data();
    exec_.program = &program;
    exec_.inputs = &in;
    run_list(program.prologue, exec_);
}

void BlockEvaluator::run(size_t begin, size_t count) {
    exec_.begin = begin;
    exec_.lanes = count;
    run_list(program_.main, exec_);
}

void BlockEvaluator::read_root(size_t count, double* to) const {
    const Operand& o = program_.root;
    const size_t comps = program_.root_comps;
    auto read = [&](const auto* values) {
        for (size_t l = 0; l < count; ++l)
            for (size_t c = 0; c < comps; ++c)
                to[l * comps + c] = double(values[o.offset + l * o.lane_step + c * o.comp_step]);
    };
    if (program_.wide)
        read(wide_.data());
    else
        read(narrow_.data());
}

} // namespace watergen
