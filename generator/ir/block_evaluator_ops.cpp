// What each IR operation computes on the CPU, over the lanes of a block: BlockEvaluator's
// compute() (block_evaluator.h), apart from the driver and loops in block_evaluator.cpp.
#include "block_evaluator.h"

#include <algorithm>
#include <cmath>

#include "texture_sampling.h"

namespace watergen {

// out = f(argument 0, argument 1) component by component, broadcasting scalars and
// lane-invariant arguments; the common shapes run as flat loops the compiler vectorises.
template <class F> void BlockEvaluator::map2(std::vector<double>& out, int comps, F f) const {
    const double *a = sources_[0], *b = sources_[1];
    const size_t la = lane_stride_[0], ca = component_stride_[0];
    const size_t lb = lane_stride_[1], cb = component_stride_[1];
    const size_t k = static_cast<size_t>(comps), total = n_ * k;
    double* o = out.data();
    if (la == k && ca == (k > 1) && lb == k && cb == (k > 1)) {
        for (size_t i = 0; i < total; ++i)
            o[i] = f(a[i], b[i]);
    } else if (la == k && ca == (k > 1) && lb == 0 && cb == 0) {
        const double y = b[0];
        for (size_t i = 0; i < total; ++i)
            o[i] = f(a[i], y);
    } else if (la == 0 && ca == 0 && lb == k && cb == (k > 1)) {
        const double x = a[0];
        for (size_t i = 0; i < total; ++i)
            o[i] = f(x, b[i]);
    } else {
        for (size_t l = 0; l < n_; ++l)
            for (size_t c = 0; c < k; ++c)
                o[l * k + c] = f(a[l * la + c * ca], b[l * lb + c * cb]);
    }
}

// Where arg() reads each argument of `n`. In half mode a relaxed node reads its 32-bit
// arguments (parameters, inputs, full-precision islands) converted to binary16, as the GPU
// converts them where 16-bit arithmetic begins; a texture sample keeps 32-bit coordinates.
bool BlockEvaluator::compute(uint32_t id, const Node& n, int comps, size_t begin,
                             std::vector<double>& out, std::string& error) {
    (void)id;
    bind_arguments(n);
    auto each = [&](auto f) {
        for (size_t l = 0; l < n_; ++l)
            for (int c = 0; c < comps; ++c)
                out[l * comps + c] = f(l, c);
    };
    auto a0 = [&](size_t l, int c) { return arg(n, 0, l, c); };
    auto a1 = [&](size_t l, int c) { return arg(n, 1, l, c); };
    auto a2 = [&](size_t l, int c) { return arg(n, 2, l, c); };
    // Half mode computes a relaxed node in binary16 steps, as a GPU does in 16-bit
    // arithmetic: r() rounds each intermediate of a composite built-in (dot, normalize,
    // mix, smoothstep, ...) in the order lavapipe's lowering uses (measured per operation
    // by tests/render/strict_half_ops_test.cpp); elsewhere r() is the identity and a
    // node is rounded once, after it is computed exactly.
    const bool stepwise = p_ == EvalPrecision::Half && n.relaxed;
    auto r = [stepwise](double v) { return stepwise ? round_to_half(v) : v; };
    auto reduce_dot = [&](size_t l, size_t i, size_t j) {
        const int k = comps_[n.args[i]];
        double s = r(arg(n, i, l, 0) * arg(n, j, l, 0));
        for (int c = 1; c < k; ++c)
            s = r(s + r(arg(n, i, l, c) * arg(n, j, l, c)));
        return s;
    };
    switch (n.op) {
    case Op::Constant:
        if (n.type == Type::Error) {
            error = "graph contains an ill-typed node";
            return false;
        }
        each([&](size_t, int c) { return n.values[c]; });
        return true;
    case Op::Uniform: {
        const std::vector<double>* v = nullptr;
        if (auto it = in_.uniforms.find(n.name); it != in_.uniforms.end())
            v = &it->second;
        else if (const Parameter* p = params_.find_parameter(n.name))
            v = &p->default_value;
        if (!v || static_cast<int>(v->size()) != comps) {
            error =
                "uniform '" + n.name + "': no value with " + std::to_string(comps) + " components";
            return false;
        }
        each([&](size_t, int c) { return (*v)[c]; });
        return true;
    }
    case Op::UniformElement: {
        const Parameter* p = params_.find_parameter(n.name);
        const std::vector<double>* v = p ? &p->default_value : nullptr;
        if (auto it = in_.uniforms.find(n.name);
            p && it != in_.uniforms.end() && it->second.size() == v->size())
            v = &it->second;
        if (!p || p->array_size == 0 || v->size() != p->array_size * size_t(comps)) {
            error = "array '" + n.name + "': no value with " + std::to_string(comps) +
                    " components per element";
            return false;
        }
        const double last = p->array_size - 1;
        each([&](size_t l, int c) {
            const double i = std::floor(a0(l, 0));
            const auto e = static_cast<size_t>(i >= 0.0 ? std::min(i, last) : 0.0); // NaN: 0
            return (*v)[e * comps + c];
        });
        return true;
    }
    case Op::Varying: {
        auto it = in_.varyings.find(n.name);
        if (it == in_.varyings.end() || it->second.size() < (begin + n_) * comps) {
            error = "varying '" + n.name + "' missing or too short";
            return false;
        }
        each([&](size_t l, int c) { return it->second[(begin + l) * comps + c]; });
        return true;
    }
    case Op::Texture:
        return true;
    case Op::Loop:
        return run_loop(id, n, begin, out, error);
    case Op::LoopResult:
    case Op::SwitchResult: {
        // Carried value / result k: its components at the loop's or switch's offset for k.
        const Node& whole = g_.node(n.args[0]);
        const std::vector<Type>& types =
            whole.loop ? whole.loop->carried_types : whole.cases->result_types;
        size_t offset = 0;
        for (size_t k = 0; k < static_cast<size_t>(n.values[0]); ++k)
            offset += static_cast<size_t>(component_count(types[k]));
        each([&](size_t l, int c) { return sources_[0][l * lane_stride_[0] + offset + c]; });
        return true;
    }
    case Op::Switch:
        return run_switch(id, n, begin, out, error);
    case Op::LoopIndex:
        each([&](size_t, int) { return frame_->index; });
        return true;
    case Op::Carried: {
        const size_t offset = frame_->carried_offset[static_cast<size_t>(n.values[0])];
        each([&](size_t l, int c) {
            return frame_->carried[l * frame_->carried_lane_stride + offset + c];
        });
        return true;
    }
    case Op::Captured: {
        const LoopFrame::Source& s = frame_->captured[static_cast<size_t>(n.values[0])];
        each([&](size_t l, int c) {
            return s.values[l * s.lane_stride + static_cast<size_t>(c) * s.component_stride];
        });
        return true;
    }
    case Op::Add:
        map2(out, comps, [](double a, double b) { return a + b; });
        return true;
    case Op::Sub:
        map2(out, comps, [](double a, double b) { return a - b; });
        return true;
    case Op::Mul:
        map2(out, comps, [](double a, double b) { return a * b; });
        return true;
    case Op::Div:
        map2(out, comps, [](double a, double b) { return a / b; });
        return true;
    case Op::Neg:
        each([&](size_t l, int c) { return -a0(l, c); });
        return true;
    case Op::Less:
        each([&](size_t l, int) { return double(a0(l, 0) < a1(l, 0)); });
        return true;
    case Op::LessEqual:
        each([&](size_t l, int) { return double(a0(l, 0) <= a1(l, 0)); });
        return true;
    case Op::Greater:
        each([&](size_t l, int) { return double(a0(l, 0) > a1(l, 0)); });
        return true;
    case Op::GreaterEqual:
        each([&](size_t l, int) { return double(a0(l, 0) >= a1(l, 0)); });
        return true;
    case Op::Equal:
        each([&](size_t l, int) { return double(a0(l, 0) == a1(l, 0)); });
        return true;
    case Op::NotEqual:
        each([&](size_t l, int) { return double(a0(l, 0) != a1(l, 0)); });
        return true;
    case Op::And:
        each([&](size_t l, int) { return double(a0(l, 0) != 0 && a1(l, 0) != 0); });
        return true;
    case Op::Or:
        each([&](size_t l, int) { return double(a0(l, 0) != 0 || a1(l, 0) != 0); });
        return true;
    case Op::Not:
        each([&](size_t l, int) { return double(a0(l, 0) == 0); });
        return true;
    case Op::Select:
        each([&](size_t l, int c) { return a0(l, 0) != 0 ? a1(l, c) : a2(l, c); });
        return true;
    case Op::Swizzle:
        each([&](size_t l, int c) { return a0(l, static_cast<int>(n.values[c])); });
        return true;
    case Op::Splat:
        each([&](size_t l, int) { return a0(l, 0); });
        return true;
    case Op::Construct: {
        // Flatten arguments in order (Mat3: three columns, column-major).
        for (size_t l = 0; l < n_; ++l) {
            int c = 0;
            for (size_t i = 0; i < n.args.size(); ++i) {
                const int k = comps_[n.args[i]];
                for (int j = 0; j < k; ++j)
                    out[l * comps + c++] = arg(n, i, l, j);
            }
        }
        return true;
    }
    case Op::Dot:
        each([&](size_t l, int) { return reduce_dot(l, 0, 1); });
        return true;
    case Op::Length:
        each([&](size_t l, int) { return std::sqrt(reduce_dot(l, 0, 0)); });
        return true;
    case Op::Normalize:
        each([&](size_t l, int c) { return a0(l, c) / r(std::sqrt(reduce_dot(l, 0, 0))); });
        return true;
    case Op::Cross:
        each([&](size_t l, int c) {
            const int i = (c + 1) % 3, j = (c + 2) % 3;
            return r(a0(l, i) * a1(l, j)) - r(a0(l, j) * a1(l, i));
        });
        return true;
    case Op::Mix:
        each([&](size_t l, int c) {
            // x + (y - x) a exactly; in binary16 steps x (1 - a) + y a, as lavapipe does.
            if (!stepwise) return a0(l, c) + (a1(l, c) - a0(l, c)) * a2(l, c);
            return r(a0(l, c) * r(1.0 - a2(l, c))) + r(a1(l, c) * a2(l, c));
        });
        return true;
    // GPUs return the non-NaN operand of min/max (IEEE minNum); fmin/fmax do the same.
    case Op::Clamp:
        each([&](size_t l, int c) { return std::fmin(std::fmax(a0(l, c), a1(l, c)), a2(l, c)); });
        return true;
    case Op::Saturate:
        each([&](size_t l, int c) { return std::fmin(std::fmax(a0(l, c), 0.0), 1.0); });
        return true;
    case Op::Min:
        each([&](size_t l, int c) { return std::fmin(a0(l, c), a1(l, c)); });
        return true;
    case Op::Max:
        each([&](size_t l, int c) { return std::fmax(a0(l, c), a1(l, c)); });
        return true;
    case Op::Pow:
        // Binary16 steps: exp2(y log2(x)), exp2(x log2(e)), log2(x) ln(2), 1 / sqrt(x).
        each([&](size_t l, int c) {
            if (!stepwise) return std::pow(a0(l, c), a1(l, c));
            return std::exp2(r(a1(l, c) * r(std::log2(a0(l, c)))));
        });
        return true;
    case Op::Exp:
        each([&](size_t l, int c) {
            return stepwise ? std::exp2(r(a0(l, c) * r(1.4426950408889634))) : std::exp(a0(l, c));
        });
        return true;
    case Op::Exp2:
        each([&](size_t l, int c) { return std::exp2(a0(l, c)); });
        return true;
    case Op::Log:
        each([&](size_t l, int c) {
            return stepwise ? r(std::log2(a0(l, c))) * r(0.69314718055994531) : std::log(a0(l, c));
        });
        return true;
    case Op::Sqrt:
        each([&](size_t l, int c) { return std::sqrt(a0(l, c)); });
        return true;
    case Op::Rsqrt:
        each([&](size_t l, int c) { return 1.0 / r(std::sqrt(a0(l, c))); });
        return true;
    case Op::Abs:
        each([&](size_t l, int c) { return std::fabs(a0(l, c)); });
        return true;
    case Op::Sign:
        each([&](size_t l, int c) {
            const double x = a0(l, c);
            return double((x > 0) - (x < 0));
        });
        return true;
    case Op::Sin:
        each([&](size_t l, int c) { return std::sin(a0(l, c)); });
        return true;
    case Op::Cos:
        each([&](size_t l, int c) { return std::cos(a0(l, c)); });
        return true;
    case Op::Atan2:
        each([&](size_t l, int c) { return std::atan2(a0(l, c), a1(l, c)); });
        return true;
    case Op::Fract:
        each([&](size_t l, int c) { return a0(l, c) - std::floor(a0(l, c)); });
        return true;
    case Op::Floor:
        each([&](size_t l, int c) { return std::floor(a0(l, c)); });
        return true;
    case Op::Mod:
        each([&](size_t l, int c) {
            return a0(l, c) - r(a1(l, c) * std::floor(r(a0(l, c) / a1(l, c))));
        });
        return true;
    case Op::Step:
        each([&](size_t l, int c) { return a1(l, c) < a0(l, c) ? 0.0 : 1.0; });
        return true;
    case Op::Smoothstep:
        each([&](size_t l, int c) {
            const double t =
                std::fmin(std::fmax(r(r(a2(l, c) - a0(l, c)) / r(a1(l, c) - a0(l, c))), 0.0), 1.0);
            return stepwise ? t * r(t * r(3.0 - r(2.0 * t))) : t * t * (3.0 - 2.0 * t);
        });
        return true;
    case Op::Reflect:
        each(
            [&](size_t l, int c) { return a0(l, c) - r(2.0 * r(reduce_dot(l, 1, 0) * a1(l, c))); });
        return true;
    case Op::Refract:
        each([&](size_t l, int c) {
            const double ni = reduce_dot(l, 1, 0), eta = a2(l, 0);
            const double k = stepwise ? r(1.0 - r(eta * r(eta * r(1.0 - r(ni * ni)))))
                                      : 1.0 - eta * eta * (1.0 - ni * ni);
            if (k < 0) return 0.0;
            return r(eta * a0(l, c)) - r(r(r(eta * ni) + r(std::sqrt(k))) * a1(l, c));
        });
        return true;
    case Op::MatMulVec:
        each([&](size_t l, int row) {
            double s = 0;
            if (!stepwise) {
                for (int k = 0; k < 3; ++k)
                    s += arg(n, 0, l, k * 3 + row) * arg(n, 1, l, k);
                return s;
            }
            // Column 2 first: the order of lavapipe's binary16 steps.
            s = r(arg(n, 0, l, 6 + row) * arg(n, 1, l, 2));
            for (int k = 1; k >= 0; --k)
                s = r(s + r(arg(n, 0, l, k * 3 + row) * arg(n, 1, l, k)));
            return s;
        });
        return true;
    case Op::Sample:
    case Op::SampleLevel: {
        const Node& tex = g_.node(n.args[0]);
        auto it = in_.textures.find(tex.name);
        if (it == in_.textures.end() || !it->second.rgba) {
            error = "texture '" + tex.name + "' not supplied";
            return false;
        }
        const TextureView& view = it->second;
        const bool cube = tex.type == Type::TextureCube;
        const uint32_t layers = cube ? 6u : 1u;
        if (view.layers != 0 && view.layers != layers) {
            error = "texture '" + tex.name + "' has " + std::to_string(view.layers) +
                    " layers; the " + (cube ? "cube" : "2D") + " binding needs " +
                    std::to_string(layers);
            return false;
        }
        if (view.width == 0 || view.height == 0 || (cube && view.width != view.height)) {
            error = "texture '" + tex.name + "': bad size" +
                    (cube ? " (cube faces must be square)" : "");
            return false;
        }
        for (size_t l = 0; l < n_; ++l) {
            double texel[4];
            if (cube)
                sample_cube(view, in_.filter, a1(l, 0), a1(l, 1), a1(l, 2), texel);
            else
                sample_2d(view, in_.filter, a1(l, 0), a1(l, 1), texel);
            for (int c = 0; c < 4; ++c)
                out[l * 4 + c] = texel[c];
        }
        return true;
    }
    case Op::Ddx:
    case Op::Ddy: {
        // Quad lanes: 0 = (0,0), 1 = (1,0), 2 = (0,1), 3 = (1,1).
        const bool dx = n.op == Op::Ddx;
        each([&](size_t l, int c) {
            const size_t q = l & ~size_t(3), i = l & 3;
            const size_t lo = dx ? q + (i & 2) : q + (i & 1);
            const size_t hi = dx ? lo + 1 : lo + 2;
            return hi < n_ ? a0(hi, c) - a0(lo, c) : 0.0;
        });
        return true;
    }
    }
    error = std::string("operation '") + op_name(n.op) + "' has no CPU evaluation";
    return false;
}

} // namespace watergen
