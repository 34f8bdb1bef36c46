// Element-wise kernels: each component of each lane from the same components of the
// arguments (scalars and lane-invariant arguments broadcast). Flat loops over a component's
// lanes, which the compiler vectorises where the operation allows.
#include "block_kernels.h"

#include <cmath>
#include <type_traits>

namespace watergen {

namespace {

// glibc's fmax and fmin, which the evaluator has always used (GPUs return the non-NaN operand
// of min/max, IEEE minNum): the other operand when one is NaN, the first when both are; the
// second when neither is greater (+0 and -0). Written out so that they vectorise.
template <class T> T max_of(T a, T b) {
    T m = a > b ? a : b;
    m = a != a ? b : m;
    return b != b ? a : m;
}
template <class T> T min_of(T a, T b) {
    T m = a < b ? a : b;
    m = a != a ? b : m;
    return b != b ? a : m;
}

// Operations computed in the storage type (exact, or + - * / whose binary32 result does not
// depend on a binary64 step first; see block_kernels.h).
struct Add {
    template <class T> static T f(T a, T b) { return a + b; }
};
struct Sub {
    template <class T> static T f(T a, T b) { return a - b; }
};
struct Mul {
    template <class T> static T f(T a, T b) { return a * b; }
};
struct Div {
    template <class T> static T f(T a, T b) { return a / b; }
};
// min(a, b) and max(a, b) have always been glibc's fmin(b, a) and fmax(b, a) here (the
// operand order the compiler chose for the calls): of +0 and -0 they give a, of two NaNs b.
struct Min {
    template <class T> static T f(T a, T b) { return min_of(b, a); }
};
struct Max {
    template <class T> static T f(T a, T b) { return max_of(b, a); }
};
struct Less {
    template <class T> static T f(T a, T b) { return T(a < b); }
};
struct LessEqual {
    template <class T> static T f(T a, T b) { return T(a <= b); }
};
struct Greater {
    template <class T> static T f(T a, T b) { return T(a > b); }
};
struct GreaterEqual {
    template <class T> static T f(T a, T b) { return T(a >= b); }
};
struct Equal {
    template <class T> static T f(T a, T b) { return T(a == b); }
};
struct NotEqual {
    template <class T> static T f(T a, T b) { return T(a != b); }
};
struct And {
    template <class T> static T f(T a, T b) { return T((a != 0) & (b != 0)); }
};
struct Or {
    template <class T> static T f(T a, T b) { return T((a != 0) | (b != 0)); }
};
struct StepEdge { // step(edge, x)
    template <class T> static T f(T edge, T x) { return x < edge ? T(0) : T(1); }
};
struct Neg {
    template <class T> static T f(T a) { return -a; }
};
struct Abs {
    template <class T> static T f(T a) { return std::fabs(a); }
};
struct Sign {
    template <class T> static T f(T a) { return T((a > 0) - (a < 0)); }
};
struct Not {
    template <class T> static T f(T a) { return T(a == 0); }
};
struct Saturate {
    template <class T> static T f(T a) { return min_of(max_of(a, T(0)), T(1)); }
};
struct Select {
    template <class T> static T f(T c, T a, T b) { return c != 0 ? a : b; }
};
struct Clamp { // fmin(hi, fmax(lo, x)) in glibc's terms, likewise
    template <class T> static T f(T x, T lo, T hi) { return min_of(hi, max_of(lo, x)); }
};

// Operations computed in double and rounded as they are stored.
struct Floor {
    template <class T> static T f(T a) { return T(std::floor(double(a))); }
};
struct Fract {
    template <class T> static T f(T a) { return T(double(a) - std::floor(double(a))); }
};
struct Sqrt {
    template <class T> static T f(T a) { return T(std::sqrt(double(a))); }
};
struct Exp2 {
    template <class T> static T f(T a) { return T(std::exp2(double(a))); }
};
struct Sin {
    template <class T> static T f(T a) { return T(std::sin(double(a))); }
};
struct Cos {
    template <class T> static T f(T a) { return T(std::cos(double(a))); }
};
struct Atan2 {
    template <class T> static T f(T y, T x) { return T(std::atan2(double(y), double(x))); }
};
// Binary16 steps: exp2(y log2(x)), exp2(x log2(e)), log2(x) ln(2), 1 / sqrt(x).
template <bool S> struct Pow {
    template <class T> static T f(T x, T y) {
        if constexpr (S)
            return T(std::exp2(half_step<S>(double(y) * half_step<S>(std::log2(double(x))))));
        else
            return T(std::pow(double(x), double(y)));
    }
};
template <bool S> struct Exp {
    template <class T> static T f(T x) {
        if constexpr (S)
            return T(std::exp2(half_step<S>(double(x) * half_step<S>(1.4426950408889634))));
        else
            return T(std::exp(double(x)));
    }
};
template <bool S> struct Log {
    template <class T> static T f(T x) {
        if constexpr (S)
            return T(half_step<S>(std::log2(double(x))) * half_step<S>(0.69314718055994531));
        else
            return T(std::log(double(x)));
    }
};
template <bool S> struct Rsqrt {
    template <class T> static T f(T x) { return T(1.0 / half_step<S>(std::sqrt(double(x)))); }
};
template <bool S> struct Mod {
    template <class T> static T f(T x, T y) {
        const double a = double(x), b = double(y);
        return T(a - half_step<S>(b * std::floor(half_step<S>(a / b))));
    }
};
// x + (y - x) a exactly; in binary16 steps x (1 - a) + y a, as lavapipe does.
template <bool S> struct Mix {
    template <class T> static T f(T x, T y, T a) {
        const double u = double(x), v = double(y), t = double(a);
        if constexpr (S)
            return T(half_step<S>(u * half_step<S>(1.0 - t)) + half_step<S>(v * t));
        else
            return T(u + (v - u) * t);
    }
};
template <bool S> struct Smoothstep {
    template <class T> static T f(T e0, T e1, T x) {
        const double a = double(e0), b = double(e1), c = double(x);
        const double t =
            min_of(max_of(half_step<S>(half_step<S>(c - a) / half_step<S>(b - a)), 0.0), 1.0);
        if constexpr (S)
            return T(t * half_step<S>(t * half_step<S>(3.0 - half_step<S>(2.0 * t))));
        else
            return T(t * t * (3.0 - 2.0 * t));
    }
};

template <class T> T* at(const Exec& ex, const Operand& o, uint32_t c) {
    return static_cast<T*>(ex.arena) + o.offset + c * o.comp_step;
}

template <class T, class F, unsigned LA> void unary(const Instr& ins, Exec& ex, size_t n) {
    for (uint32_t c = 0; c < ins.comps; ++c) {
        T* __restrict o = at<T>(ex, ins.out, c);
        const T* __restrict a = at<T>(ex, ins.args[0], c);
        for (size_t l = 0; l < n; ++l)
            o[l] = F::f(a[l * LA]);
    }
}

template <class T, class F, unsigned LA, unsigned LB>
void binary(const Instr& ins, Exec& ex, size_t n) {
    for (uint32_t c = 0; c < ins.comps; ++c) {
        T* __restrict o = at<T>(ex, ins.out, c);
        const T* __restrict a = at<T>(ex, ins.args[0], c);
        const T* __restrict b = at<T>(ex, ins.args[1], c);
        for (size_t l = 0; l < n; ++l)
            o[l] = F::f(a[l * LA], b[l * LB]);
    }
}

// Three arguments: rarer, so one flat loop for all-per-lane arguments and a strided one else.
template <class T, class F> void ternary(const Instr& ins, Exec& ex, size_t n) {
    const size_t la = ins.args[0].lane_step, lb = ins.args[1].lane_step;
    const size_t lc = ins.args[2].lane_step;
    for (uint32_t c = 0; c < ins.comps; ++c) {
        T* __restrict o = at<T>(ex, ins.out, c);
        const T* __restrict a = at<T>(ex, ins.args[0], c);
        const T* __restrict b = at<T>(ex, ins.args[1], c);
        const T* __restrict d = at<T>(ex, ins.args[2], c);
        if (la == 1 && lb == 1 && lc == 1) {
            for (size_t l = 0; l < n; ++l)
                o[l] = F::f(a[l], b[l], d[l]);
        } else {
            for (size_t l = 0; l < n; ++l)
                o[l] = F::f(a[l * la], b[l * lb], d[l * lc]);
        }
    }
}

template <class T, class F> Kernel pick1(uint32_t la) {
    return la ? unary<T, F, 1> : unary<T, F, 0>;
}
template <class T, class F> Kernel pick2(uint32_t la, uint32_t lb) {
    if (la && lb) return binary<T, F, 1, 1>;
    if (la) return binary<T, F, 1, 0>;
    if (lb) return binary<T, F, 0, 1>;
    return binary<T, F, 0, 0>;
}
// The binary16-step form only where values are stored as float (the half mode).
template <class T, template <bool> class F> Kernel pick1s(bool step, uint32_t la) {
    if constexpr (std::is_same_v<T, float>)
        if (step) return pick1<T, F<true>>(la);
    return pick1<T, F<false>>(la);
}
template <class T, template <bool> class F> Kernel pick2s(bool step, uint32_t la, uint32_t lb) {
    if constexpr (std::is_same_v<T, float>)
        if (step) return pick2<T, F<true>>(la, lb);
    return pick2<T, F<false>>(la, lb);
}
template <class T, template <bool> class F> Kernel pick3s(bool step) {
    if constexpr (std::is_same_v<T, float>)
        if (step) return ternary<T, F<true>>;
    return ternary<T, F<false>>;
}

template <class T> Kernel elementwise(Op op, bool step, uint32_t la, uint32_t lb) {
    switch (op) {
    case Op::Add:
        return pick2<T, Add>(la, lb);
    case Op::Sub:
        return pick2<T, Sub>(la, lb);
    case Op::Mul:
        return pick2<T, Mul>(la, lb);
    case Op::Div:
        return pick2<T, Div>(la, lb);
    case Op::Min:
        return pick2<T, Min>(la, lb);
    case Op::Max:
        return pick2<T, Max>(la, lb);
    case Op::Less:
        return pick2<T, Less>(la, lb);
    case Op::LessEqual:
        return pick2<T, LessEqual>(la, lb);
    case Op::Greater:
        return pick2<T, Greater>(la, lb);
    case Op::GreaterEqual:
        return pick2<T, GreaterEqual>(la, lb);
    case Op::Equal:
        return pick2<T, Equal>(la, lb);
    case Op::NotEqual:
        return pick2<T, NotEqual>(la, lb);
    case Op::And:
        return pick2<T, And>(la, lb);
    case Op::Or:
        return pick2<T, Or>(la, lb);
    case Op::Step:
        return pick2<T, StepEdge>(la, lb);
    case Op::Atan2:
        return pick2<T, Atan2>(la, lb);
    case Op::Pow:
        return pick2s<T, Pow>(step, la, lb);
    case Op::Mod:
        return pick2s<T, Mod>(step, la, lb);
    case Op::Neg:
        return pick1<T, Neg>(la);
    case Op::Abs:
        return pick1<T, Abs>(la);
    case Op::Sign:
        return pick1<T, Sign>(la);
    case Op::Not:
        return pick1<T, Not>(la);
    case Op::Saturate:
        return pick1<T, Saturate>(la);
    case Op::Floor:
        return pick1<T, Floor>(la);
    case Op::Fract:
        return pick1<T, Fract>(la);
    case Op::Sqrt:
        return pick1<T, Sqrt>(la);
    case Op::Exp2:
        return pick1<T, Exp2>(la);
    case Op::Sin:
        return pick1<T, Sin>(la);
    case Op::Cos:
        return pick1<T, Cos>(la);
    case Op::Exp:
        return pick1s<T, Exp>(step, la);
    case Op::Log:
        return pick1s<T, Log>(step, la);
    case Op::Rsqrt:
        return pick1s<T, Rsqrt>(step, la);
    case Op::Select:
        return ternary<T, Select>;
    case Op::Clamp:
        return ternary<T, Clamp>;
    case Op::Mix:
        return pick3s<T, Mix>(step);
    case Op::Smoothstep:
        return pick3s<T, Smoothstep>(step);
    default:
        return nullptr;
    }
}

} // namespace

Kernel op_kernel(Op op, bool wide, bool stepwise, uint32_t lane_step0, uint32_t lane_step1) {
    const Kernel k = wide ? elementwise<double>(op, stepwise, lane_step0, lane_step1)
                          : elementwise<float>(op, stepwise, lane_step0, lane_step1);
    return k ? k : data_kernel(op, wide, stepwise, lane_step0, lane_step1);
}

} // namespace watergen
