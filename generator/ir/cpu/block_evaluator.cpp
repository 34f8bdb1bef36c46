// BlockEvaluator: the run over a program's instructions, and loops.
#include "block_evaluator.h"

#include <algorithm>
#include <cstdint>

#include "block_kernels.h"

namespace watergen {

namespace {

// splitmix64's finaliser: a well-mixed 64-bit value from any.
uint64_t mix(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

// FloatPerturbation on a double instruction's results (cpu_evaluator.h).
void perturb(const Instr& ins, Exec& ex, size_t lanes) {
    const FloatPerturbation& p = *ex.perturbation;
    const auto site = static_cast<int64_t>(ins.site);
    const bool round_here = site >= p.round_first && site < p.round_end;
    if (!round_here && (p.relative <= 0 || ins.exact)) return;
    double* m = static_cast<double*>(ex.arena);
    const uint64_t key = mix(p.seed ^ mix(uint64_t(ins.site) << 20 ^ uint64_t(ex.loop_index)));
    for (uint32_t c = 0; c < ins.comps; ++c)
        for (size_t l = 0; l < lanes; ++l) {
            double& v = m[ins.out.offset + l * ins.out.lane_step + c * ins.out.comp_step];
            if (round_here) {
                v = static_cast<double>(static_cast<float>(v));
                continue;
            }
            const uint64_t lane = ins.per_lane ? ex.begin + l : 0;
            // Uniform in [-1, 1): the top 53 bits of the lane's hash as a fraction.
            const uint64_t r = mix(key ^ (lane << 3 | c));
            v *= 1.0 + p.relative * (static_cast<double>(r >> 11) * 0x1p-52 - 1.0);
        }
}

void run_list(const std::vector<Instr>& list, Exec& ex) {
    for (const Instr& ins : list) {
        const size_t lanes = ins.per_lane ? ex.lanes : 1;
        ins.kernel(ins, ex, lanes);
        if (ins.round != Rounding::None) round_result(ins, ex, lanes);
        if (ex.perturbation && ins.site != UINT32_MAX) perturb(ins, ex, lanes);
    }
}

// Lanes [0, n) of a carried value's row from a row that varies per lane (lane step 1) or not
// (0); with `active`, only the lanes still in the loop. Both forms vectorise.
template <class T>
void copy_lanes(T* __restrict to, const T* __restrict from, uint32_t lane_step, size_t n,
                const unsigned char* active = nullptr) {
    if (lane_step == 0) {
        const T v = *from;
        for (size_t l = 0; l < n; ++l)
            to[l] = active && !active[l] ? to[l] : v;
    } else if (!active) {
        std::copy_n(from, n, to);
    } else {
        for (size_t l = 0; l < n; ++l)
            to[l] = active[l] ? from[l] : to[l];
    }
}

template <class T> void run_loop(const Instr& ins, Exec& ex, size_t n) {
    const LoopPlan& loop = ex.program->loops[ins.aux];
    T* m = static_cast<T*>(ex.arena);
    auto row = [&](const Operand& o, uint32_t c) { return m + o.offset + c * o.comp_step; };
    for (const auto& k : loop.carried)
        for (uint32_t c = 0; c < k.comps; ++c) // a lane-invariant value: one lane
            copy_lanes(row(k.storage, c), row(k.initial, c), k.initial.lane_step,
                       k.storage.lane_step ? n : 1);
    unsigned char active[kBlock];
    std::fill_n(active, n, 1);
    size_t remaining = n;
    // A trip count from data is the same on every lane (dsl.h checks it) and floored; a NaN
    // fails the comparison as it fails the GPU's.
    int trips = loop.trip_count;
    if (loop.counted) {
        const double count = double(m[loop.count.offset]); // the block's first lane
        trips = count >= 1.0 ? static_cast<int>(std::min(count, double(trips))) : 0;
    }
    const double outer_index = ex.loop_index;
    for (int i = 0; i < trips && remaining > 0; ++i) {
        ex.loop_index = i;
        run_list(loop.body, ex);
        for (const auto& k : loop.carried)
            for (uint32_t c = 0; c < k.comps; ++c)
                copy_lanes(row(k.storage, c), row(k.next, c), k.next.lane_step,
                           k.storage.lane_step ? n : 1, remaining == n ? nullptr : active);
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
    if (program.wide && in.perturbation.active()) exec_.perturbation = &in.perturbation;
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
