// Kernels beyond the element-wise ones (block_kernels.cpp): leaves, copies, texture sampling,
// derivatives, and the composite built-ins that combine components (dot, normalize, cross,
// reflect, refract, mat3 * vec3).
#include "block_kernels.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "texture_sampling.h"

namespace watergen {

namespace {

// Reads an operand's values as doubles.
template <class T> struct In {
    const T* p;
    size_t lane_step, comp_step;
    In(const Exec& ex, const Operand& o)
        : p(static_cast<const T*>(ex.arena) + o.offset), lane_step(o.lane_step),
          comp_step(o.comp_step) {}
    double operator()(size_t l, uint32_t c) const {
        return double(p[l * lane_step + c * comp_step]);
    }
};

// Writes an instruction's result: component c of lane l.
template <class T> struct Out {
    T* p;
    size_t comp_step;
    explicit Out(const Exec& ex, const Instr& ins)
        : p(static_cast<T*>(ex.arena) + ins.out.offset), comp_step(ins.out.comp_step) {}
    T& operator()(size_t l, uint32_t c) const { return p[l + c * comp_step]; }
};

// Sum of products of `comps` components, left to right (a binary16 step each in half mode).
template <bool S, class T>
double reduce_dot(const In<T>& a, const In<T>& b, size_t l, uint32_t comps) {
    double s = half_step<S>(a(l, 0) * b(l, 0));
    for (uint32_t c = 1; c < comps; ++c)
        s = half_step<S>(s + half_step<S>(a(l, c) * b(l, c)));
    return s;
}

// dot(a, b) over whole rows of lanes, so that it vectorises. aux: the arguments' components.
template <class T, bool S, unsigned LA, unsigned LB>
void dot(const Instr& ins, Exec& ex, size_t n) {
    const T* m = static_cast<const T*>(ex.arena);
    const Operand &x = ins.args[0], &y = ins.args[1];
    double s[kBlock];
    for (uint32_t c = 0; c < ins.aux; ++c) {
        const T* __restrict a = m + x.offset + c * x.comp_step;
        const T* __restrict b = m + y.offset + c * y.comp_step;
        if (c == 0) {
            for (size_t l = 0; l < n; ++l)
                s[l] = half_step<S>(double(a[l * LA]) * double(b[l * LB]));
        } else {
            for (size_t l = 0; l < n; ++l)
                s[l] = half_step<S>(s[l] + half_step<S>(double(a[l * LA]) * double(b[l * LB])));
        }
    }
    T* __restrict o = static_cast<T*>(ex.arena) + ins.out.offset;
    for (size_t l = 0; l < n; ++l)
        o[l] = T(s[l]);
}

template <class T, bool S> void length(const Instr& ins, Exec& ex, size_t n) {
    const In<T> a(ex, ins.args[0]);
    const Out<T> o(ex, ins);
    for (size_t l = 0; l < n; ++l)
        o(l, 0) = T(std::sqrt(reduce_dot<S>(a, a, l, ins.aux)));
}

template <class T, bool S> void normalize(const Instr& ins, Exec& ex, size_t n) {
    const In<T> a(ex, ins.args[0]);
    const Out<T> o(ex, ins);
    for (size_t l = 0; l < n; ++l) {
        const double len = half_step<S>(std::sqrt(reduce_dot<S>(a, a, l, ins.aux)));
        for (uint32_t c = 0; c < ins.comps; ++c)
            o(l, c) = T(a(l, c) / len);
    }
}

template <class T, bool S> void cross(const Instr& ins, Exec& ex, size_t n) {
    const In<T> a(ex, ins.args[0]), b(ex, ins.args[1]);
    const Out<T> o(ex, ins);
    for (size_t l = 0; l < n; ++l)
        for (uint32_t c = 0; c < 3; ++c) {
            const uint32_t i = (c + 1) % 3, j = (c + 2) % 3;
            o(l, c) = T(half_step<S>(a(l, i) * b(l, j)) - half_step<S>(a(l, j) * b(l, i)));
        }
}

// reflect(i, n) = i - 2 dot(n, i) n. aux: components of n.
template <class T, bool S> void reflect(const Instr& ins, Exec& ex, size_t n) {
    const In<T> a(ex, ins.args[0]), b(ex, ins.args[1]);
    const Out<T> o(ex, ins);
    for (size_t l = 0; l < n; ++l) {
        const double d = reduce_dot<S>(b, a, l, ins.aux);
        for (uint32_t c = 0; c < ins.comps; ++c)
            o(l, c) = T(a(l, c) - half_step<S>(2.0 * half_step<S>(d * b(l, c))));
    }
}

template <class T, bool S> void refract(const Instr& ins, Exec& ex, size_t n) {
    const In<T> a(ex, ins.args[0]), b(ex, ins.args[1]), e(ex, ins.args[2]);
    const Out<T> o(ex, ins);
    for (size_t l = 0; l < n; ++l) {
        const double ni = reduce_dot<S>(b, a, l, ins.aux), eta = e(l, 0);
        const double k =
            S ? half_step<S>(
                    1.0 - half_step<S>(
                              eta * half_step<S>(eta * half_step<S>(1.0 - half_step<S>(ni * ni)))))
              : 1.0 - eta * eta * (1.0 - ni * ni);
        for (uint32_t c = 0; c < ins.comps; ++c)
            o(l, c) = k < 0 ? T(0) // total internal reflection
                            : T(half_step<S>(eta * a(l, c)) -
                                half_step<S>(half_step<S>(half_step<S>(eta * ni) +
                                                          half_step<S>(std::sqrt(k))) *
                                             b(l, c)));
    }
}

template <class T, bool S> void mat_mul_vec(const Instr& ins, Exec& ex, size_t n) {
    const In<T> m(ex, ins.args[0]), v(ex, ins.args[1]);
    const Out<T> o(ex, ins);
    for (size_t l = 0; l < n; ++l)
        for (uint32_t row = 0; row < 3; ++row) {
            double s = 0;
            if constexpr (!S) {
                for (uint32_t k = 0; k < 3; ++k)
                    s += m(l, k * 3 + row) * v(l, k);
            } else { // column 2 first: the order of lavapipe's binary16 steps
                s = half_step<S>(m(l, 6 + row) * v(l, 2));
                for (int k = 1; k >= 0; --k)
                    s = half_step<S>(s +
                                     half_step<S>(m(l, uint32_t(k) * 3 + row) * v(l, uint32_t(k))));
            }
            o(l, row) = T(s);
        }
}

// Constants and parameters: data holds the components.
template <class T> void fill(const Instr& ins, Exec& ex, size_t n) {
    const auto* v = static_cast<const double*>(ins.data);
    const Out<T> o(ex, ins);
    for (uint32_t c = 0; c < ins.comps; ++c)
        for (size_t l = 0; l < n; ++l)
            o(l, c) = T(v[c]);
}

// A varying: data holds lanes x components, lane-major.
template <class T> void varying(const Instr& ins, Exec& ex, size_t n) {
    const auto* v = static_cast<const double*>(ins.data) + ex.begin * ins.comps;
    const Out<T> o(ex, ins);
    for (uint32_t c = 0; c < ins.comps; ++c)
        for (size_t l = 0; l < n; ++l)
            o(l, c) = T(v[l * ins.comps + c]);
}

// An array parameter's element: index floored and clamped alike on GPU and CPU (NaN: 0).
// data: the elements' components; aux: the element count.
template <class T> void element(const Instr& ins, Exec& ex, size_t n) {
    const auto* v = static_cast<const double*>(ins.data);
    const In<T> index(ex, ins.args[0]);
    const Out<T> o(ex, ins);
    const double last = ins.aux - 1;
    for (size_t l = 0; l < n; ++l) {
        const double i = std::floor(index(l, 0));
        const auto e = static_cast<size_t>(i >= 0.0 ? std::min(i, last) : 0.0);
        for (uint32_t c = 0; c < ins.comps; ++c)
            o(l, c) = T(v[e * ins.comps + c]);
    }
}

template <class T> void loop_index(const Instr& ins, Exec& ex, size_t n) {
    const Out<T> o(ex, ins);
    for (uint32_t c = 0; c < ins.comps; ++c)
        for (size_t l = 0; l < n; ++l)
            o(l, c) = T(ex.loop_index);
}

// data: the TextureView; aux: 1 for a cube map. Argument 1: the coordinates.
template <class T> void sample(const Instr& ins, Exec& ex, size_t n) {
    const auto& view = *static_cast<const TextureView*>(ins.data);
    const Filter filter = ex.inputs->filter;
    const In<T> uv(ex, ins.args[1]);
    const Out<T> o(ex, ins);
    for (size_t l = 0; l < n; ++l) {
        double texel[4];
        if (ins.aux)
            sample_cube(view, filter, uv(l, 0), uv(l, 1), uv(l, 2), texel);
        else
            sample_2d(view, filter, uv(l, 0), uv(l, 1), texel);
        for (uint32_t c = 0; c < 4; ++c)
            o(l, c) = T(texel[c]);
    }
}

// Quad lanes: 0 = (0,0), 1 = (1,0), 2 = (0,1), 3 = (1,1). A quad's difference of the same
// value is 0 (NaN for an infinite one), and 0 past the end of a block.
template <class T, bool Dx> void derivative(const Instr& ins, Exec& ex, size_t n) {
    const In<T> a(ex, ins.args[0]);
    const Out<T> o(ex, ins);
    for (uint32_t c = 0; c < ins.comps; ++c)
        for (size_t l = 0; l < n; ++l) {
            const size_t q = l & ~size_t(3), i = l & 3;
            const size_t lo = Dx ? q + (i & 2) : q + (i & 1);
            const size_t hi = Dx ? lo + 1 : lo + 2;
            o(l, c) = hi < n ? T(a(hi, c) - a(lo, c)) : T(0);
        }
}

template <class T> void copy(const Instr& ins, Exec& ex, size_t n) {
    const Operand* from = ex.program->gathers.data() + ins.aux;
    T* m = static_cast<T*>(ex.arena);
    for (uint32_t c = 0; c < ins.comps; ++c) {
        T* __restrict o = m + ins.out.offset + c * ins.out.comp_step;
        const T* __restrict a = m + from[c].offset;
        if (from[c].lane_step)
            std::copy_n(a, n, o);
        else
            std::fill_n(o, n, *a);
    }
}

template <bool TowardZero> void narrow(const Instr& ins, Exec& ex, size_t n) {
    const In<float> a(ex, ins.args[0]);
    const Out<float> o(ex, ins);
    for (uint32_t c = 0; c < ins.comps; ++c)
        for (size_t l = 0; l < n; ++l)
            o(l, c) =
                float(TowardZero ? round_to_half_toward_zero(a(l, c)) : round_to_half(a(l, c)));
}

template <class T, bool S> Kernel composite(Op op, uint32_t la, uint32_t lb) {
    switch (op) {
    case Op::Dot:
        if (la && lb) return dot<T, S, 1, 1>;
        if (la) return dot<T, S, 1, 0>;
        if (lb) return dot<T, S, 0, 1>;
        return dot<T, S, 0, 0>;
    case Op::Length:
        return length<T, S>;
    case Op::Normalize:
        return normalize<T, S>;
    case Op::Cross:
        return cross<T, S>;
    case Op::Reflect:
        return reflect<T, S>;
    case Op::Refract:
        return refract<T, S>;
    case Op::MatMulVec:
        return mat_mul_vec<T, S>;
    default:
        return nullptr;
    }
}

template <class T> Kernel data(Op op, bool step, uint32_t la, uint32_t lb) {
    switch (op) {
    case Op::Constant:
    case Op::Uniform:
        return fill<T>;
    case Op::Varying:
        return varying<T>;
    case Op::UniformElement:
        return element<T>;
    case Op::LoopIndex:
        return loop_index<T>;
    case Op::Sample:
    case Op::SampleLevel:
        return sample<T>;
    case Op::Ddx:
        return derivative<T, true>;
    case Op::Ddy:
        return derivative<T, false>;
    default:
        break;
    }
    if constexpr (std::is_same_v<T, float>)
        if (step) return composite<T, true>(op, la, lb);
    return composite<T, false>(op, la, lb);
}

} // namespace

Kernel data_kernel(Op op, bool wide, bool stepwise, uint32_t lane_step0, uint32_t lane_step1) {
    return wide ? data<double>(op, stepwise, lane_step0, lane_step1)
                : data<float>(op, stepwise, lane_step0, lane_step1);
}

Kernel copy_kernel(bool wide) {
    return wide ? copy<double> : copy<float>;
}

Kernel narrow_kernel(bool toward_zero) {
    return toward_zero ? narrow<true> : narrow<false>;
}

void round_result(const Instr& ins, Exec& ex, size_t n) {
    const Out<float> o(ex, ins);
    for (uint32_t c = 0; c < ins.comps; ++c)
        for (size_t l = 0; l < n; ++l) {
            float& v = o(l, c);
            v = float(ins.round == Rounding::HalfTowardZero ? round_to_half_toward_zero(v)
                                                            : round_to_half(v));
        }
}

} // namespace watergen
