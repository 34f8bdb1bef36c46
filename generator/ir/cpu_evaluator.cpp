#include "watergen/ir/cpu_evaluator.h"

#include "texture_sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

namespace watergen {

const char* to_string(EvalPrecision p) {
    switch (p) {
    case EvalPrecision::Double:
        return "double";
    case EvalPrecision::Float:
        return "float";
    case EvalPrecision::Half:
        return "half";
    }
    return "?";
}

double round_to_half(double v) {
    if (!std::isfinite(v) || v == 0.0) return v;
    const double a = std::fabs(v);
    // 65504 is the largest half; values from the midpoint to 65536 upwards round to infinity.
    if (a >= 65520.0) return std::copysign(std::numeric_limits<double>::infinity(), v);
    int e = 0;
    std::frexp(a, &e);                         // a in [2^(e-1), 2^e)
    const int exponent = std::max(e - 1, -14); // below 2^-14 the spacing stays 2^-24
    const double ulp = std::ldexp(1.0, exponent - 10);
    return std::copysign(std::nearbyint(a / ulp) * ulp, v);
}

namespace {

// Position of a binary16 value on the number line in ulps: the count of binary16 values between
// +0 and it (negative below zero), infinity one past 65504.
int64_t half_ordinal(double v) {
    const double a = std::fabs(round_to_half(v));
    int64_t n = 0;
    if (std::isinf(a)) {
        n = 31 * 1024; // exponents 0..30 hold 1024 values each
    } else if (a < 0x1p-14) {
        n = static_cast<int64_t>(a / 0x1p-24); // subnormals: spacing 2^-24
    } else {
        int e = 0;
        const double m = std::frexp(a, &e); // a = m 2^e, m in [0.5, 1)
        n = int64_t(e + 14) * 1024 + static_cast<int64_t>((m * 2 - 1) * 1024);
    }
    return std::signbit(v) ? -n : n;
}

} // namespace

int64_t half_ulp_distance(double a, double b) {
    if (std::isnan(a) || std::isnan(b)) return -1;
    const int64_t d = half_ordinal(a) - half_ordinal(b);
    return d < 0 ? -d : d;
}

void HalfAgreement::add(double test, double reference, size_t index) {
    if (!std::isfinite(test) || !std::isfinite(reference)) return;
    const int64_t d = half_ulp_distance(test, reference);
    ++values;
    equal += d == 0;
    within_1 += d <= 1;
    if (d > max_ulps) {
        max_ulps = d;
        max_index = index;
    }
}

double round_to_half_toward_zero(double v) {
    const double r = round_to_half(v);
    if (!std::isfinite(v) || std::fabs(r) <= std::fabs(v)) return r;
    if (std::isinf(r)) return std::copysign(65504.0, v);
    // Rounded away from zero: one binary16 step back. Below a power of two the spacing is
    // half the one above it.
    const double a = std::fabs(r);
    int e = 0;
    const double m = std::frexp(a, &e); // a = m 2^e, m in [0.5, 1)
    const int exponent = std::max(e - 1 - (m == 0.5 ? 1 : 0), -14);
    return std::copysign(a - std::ldexp(1.0, exponent - 10), v);
}

double round_to(double v, EvalPrecision p) {
    switch (p) {
    case EvalPrecision::Double:
        return v;
    case EvalPrecision::Float:
        return static_cast<double>(static_cast<float>(v));
    case EvalPrecision::Half:
        return round_to_half(static_cast<double>(static_cast<float>(v)));
    }
    return v;
}

namespace {

constexpr size_t kBlock = 256; // lanes per block: a multiple of 4 (whole quads)

// Evaluates the live nodes of a graph over a block of lanes. A node whose arguments are all the
// same on every lane (constants, parameters and what is computed from them alone) is computed
// once, for one lane, and read by every lane after that: a lane-invariant node.
class BlockEvaluator {
  public:
    BlockEvaluator(const Graph& g, const std::vector<uint32_t>& live, const EvalInputs& in,
                   EvalPrecision p)
        : g_(g), live_(live), in_(in), p_(p), values_(g.size()), invariant_(g.size(), 0),
          done_(g.size(), 0), comps_(g.size(), 1) {
        // A per-lane value's storage goes back to the pool after its last user: the working
        // set is the values alive at once, not the whole graph (2304 nodes for Gerstner).
        last_use_.assign(g.size(), 0);
        for (size_t k = 0; k < live_.size(); ++k)
            for (uint32_t a : g_.node(live_[k]).args)
                last_use_[a] = k;
        for (uint32_t id : live_) {
            const Node& n = g_.node(id);
            comps_[id] = component_count(n.type);
            // Derivatives stay per lane: a quad's difference of the same value is 0, or NaN
            // for an infinite one, and 0 past the end of a block.
            bool invariant = n.op != Op::Varying && n.op != Op::Ddx && n.op != Op::Ddy;
            for (uint32_t a : n.args)
                invariant = invariant && invariant_[a];
            invariant_[id] = invariant;
        }
    }

    // Evaluates lanes [begin, begin + count) and keeps node `keep` (the output) until the
    // next run; returns false and sets error on bad input.
    bool run(size_t begin, size_t count, uint32_t keep, std::string& error) {
        for (size_t k = 0; k < live_.size(); ++k) {
            const uint32_t id = live_[k];
            if (invariant_[id] && done_[id]) continue; // the same for every block
            const Node& node = g_.node(id);
            n_ = invariant_[id] ? 1 : count;
            const int comps = comps_[id];
            auto& out = values_[id];
            if (out.capacity() == 0 && !pool_.empty()) {
                out.swap(pool_.back());
                pool_.pop_back();
            }
            out.resize(n_ * static_cast<size_t>(std::max(comps, 1)));
            if (!compute(id, node, comps, begin, out, error)) return false;
            done_[id] = 1;
            for (uint32_t a : node.args)
                if (last_use_[a] == k && !invariant_[a] && a != keep) {
                    pool_.emplace_back();
                    pool_.back().swap(values_[a]);
                }
            // Half mode: relaxed nodes are binary16, the rest binary32, as a GPU that honours
            // mediump at 16 bits would compute them.
            const EvalPrecision p =
                (p_ == EvalPrecision::Half && !node.relaxed) ? EvalPrecision::Float : p_;
            if (p == EvalPrecision::Half && texture_result(id)) {
                for (double& v : out)
                    v = round_to_half_toward_zero(static_cast<float>(v));
            } else if (p == EvalPrecision::Float) {
                for (double& v : out)
                    v = static_cast<double>(static_cast<float>(v));
            } else if (p == EvalPrecision::Half) {
                for (double& v : out)
                    v = round_to(v, p);
            }
        }
        return true;
    }

    // The values of node id, lane-major; a lane-invariant node holds one lane.
    const double* values(uint32_t id) const { return values_[id].data(); }
    bool invariant(uint32_t id) const { return invariant_[id]; }

  private:
    // Component c of argument i at lane l, broadcasting scalars and lane-invariant arguments.
    double arg(const Node&, size_t i, size_t l, int c) const {
        return sources_[i][l * lane_stride_[i] + static_cast<size_t>(c) * component_stride_[i]];
    }

    // out = f(argument 0, argument 1) component by component, broadcasting scalars and
    // lane-invariant arguments; the common shapes run as flat loops the compiler vectorises.
    template <class F> void map2(std::vector<double>& out, int comps, F f) const {
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
    void bind_arguments(const Node& n) {
        const size_t count = n.args.size();
        sources_.resize(count);
        lane_stride_.resize(count);
        component_stride_.resize(count);
        narrowed_.resize(count);
        const bool narrow =
            p_ == EvalPrecision::Half && n.relaxed && n.op != Op::Sample && n.op != Op::SampleLevel;
        for (size_t i = 0; i < count; ++i) {
            const uint32_t id = n.args[i];
            const Node& a = g_.node(id);
            const size_t comps = static_cast<size_t>(std::max(comps_[id], 1));
            sources_[i] = values_[id].data();
            lane_stride_[i] = invariant_[id] ? 0 : comps;
            component_stride_[i] = comps == 1 ? 0 : 1;
            if (!narrow || a.relaxed || !(is_float_numeric(a.type) || a.type == Type::Mat3))
                continue;
            narrowed_[i] = values_[id];
            const bool toward_zero = texture_result(id);
            for (double& v : narrowed_[i])
                v = toward_zero ? round_to_half_toward_zero(v) : round_to_half(v);
            sources_[i] = narrowed_[i].data();
        }
    }

    // A texture sample, or components of one. lavapipe converts these to binary16 rounding
    // toward zero (NIR folds the conversion into the sampler), other values to nearest.
    bool texture_result(uint32_t id) const {
        const Node& n = g_.node(id);
        if (n.op == Op::Swizzle) return texture_result(n.args[0]);
        return n.op == Op::Sample || n.op == Op::SampleLevel;
    }

    bool compute(uint32_t id, const Node& n, int comps, size_t begin, std::vector<double>& out,
                 std::string& error) {
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
            else if (const Parameter* p = g_.find_parameter(n.name))
                v = &p->default_value;
            if (!v || static_cast<int>(v->size()) != comps) {
                error = "uniform '" + n.name + "': no value with " + std::to_string(comps) +
                        " components";
                return false;
            }
            each([&](size_t, int c) { return (*v)[c]; });
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
            each([&](size_t l, int c) {
                return std::fmin(std::fmax(a0(l, c), a1(l, c)), a2(l, c));
            });
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
                return stepwise ? std::exp2(r(a0(l, c) * r(1.4426950408889634)))
                                : std::exp(a0(l, c));
            });
            return true;
        case Op::Exp2:
            each([&](size_t l, int c) { return std::exp2(a0(l, c)); });
            return true;
        case Op::Log:
            each([&](size_t l, int c) {
                return stepwise ? r(std::log2(a0(l, c))) * r(0.69314718055994531)
                                : std::log(a0(l, c));
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
                const double t = std::fmin(
                    std::fmax(r(r(a2(l, c) - a0(l, c)) / r(a1(l, c) - a0(l, c))), 0.0), 1.0);
                return stepwise ? t * r(t * r(3.0 - r(2.0 * t))) : t * t * (3.0 - 2.0 * t);
            });
            return true;
        case Op::Reflect:
            each([&](size_t l, int c) {
                return a0(l, c) - r(2.0 * r(reduce_dot(l, 1, 0) * a1(l, c)));
            });
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

    const Graph& g_;
    const std::vector<uint32_t>& live_;
    const EvalInputs& in_;
    EvalPrecision p_;
    std::vector<std::vector<double>> values_;
    std::vector<char> invariant_, done_;    // per node: lane-invariant; computed already
    std::vector<size_t> last_use_;          // per node: position in live_ of its last user
    std::vector<int> comps_;                // per node: component_count of its type
    std::vector<std::vector<double>> pool_; // storage of values no longer needed
    size_t n_ = 0;                          // lanes of the node being computed
    // Of the node being computed, per argument: its values, and the steps between lanes (0 for
    // a lane-invariant argument) and between components (0 for a scalar).
    std::vector<const double*> sources_;
    std::vector<size_t> lane_stride_, component_stride_;
    std::vector<std::vector<double>> narrowed_;
};

std::optional<uint32_t> find_output(const Graph& g, const std::string& name) {
    for (const auto& o : g.outputs())
        if (o.name == name) return o.node;
    return std::nullopt;
}

// Ids reachable from one node, ascending.
std::vector<uint32_t> live_from(const Graph& g, uint32_t root) {
    std::vector<char> live(g.size(), 0);
    std::vector<uint32_t> stack{root};
    while (!stack.empty()) {
        const uint32_t id = stack.back();
        stack.pop_back();
        if (live[id]) continue;
        live[id] = 1;
        for (uint32_t a : g.node(id).args)
            stack.push_back(a);
    }
    std::vector<uint32_t> ids;
    for (uint32_t i = 0; i < g.size(); ++i)
        if (live[i]) ids.push_back(i);
    return ids;
}

} // namespace

EvalResult evaluate(const Graph& g, const std::string& output, const EvalInputs& inputs,
                    EvalPrecision precision) {
    EvalResult result;
    const auto root = find_output(g, output);
    if (!root) {
        result.error = "graph has no output '" + output + "'";
        return result;
    }
    if (has_errors(g.diagnostics())) {
        result.error = "graph has type errors";
        return result;
    }
    result.components = component_count(g.node(*root).type);
    result.values.resize(inputs.lanes * static_cast<size_t>(result.components));
    const std::vector<uint32_t> live = live_from(g, *root);
    // Blocks are shared out to the threads in turn; each thread has its own evaluator, and a
    // lane's value does not depend on which thread computes it.
    const size_t blocks = (inputs.lanes + kBlock - 1) / kBlock;
    const size_t wanted = inputs.threads ? inputs.threads : std::thread::hardware_concurrency();
    const size_t threads = std::max<size_t>(1, std::min<size_t>(wanted, blocks));
    std::vector<std::string> errors(blocks);
    auto work = [&](size_t first) {
        BlockEvaluator block(g, live, inputs, precision);
        const size_t comps = static_cast<size_t>(result.components);
        for (size_t b = first; b < blocks; b += threads) {
            const size_t begin = b * kBlock, count = std::min(kBlock, inputs.lanes - begin);
            if (!block.run(begin, count, *root, errors[b])) return;
            const double* v = block.values(*root);
            double* to = result.values.data() + begin * comps;
            if (block.invariant(*root)) {
                for (size_t l = 0; l < count; ++l)
                    std::copy_n(v, comps, to + l * comps);
            } else {
                std::copy_n(v, count * comps, to);
            }
        }
    };
    std::vector<std::thread> pool;
    for (size_t t = 1; t < threads; ++t)
        pool.emplace_back(work, t);
    work(0);
    for (auto& t : pool)
        t.join();
    for (const auto& e : errors)
        if (!e.empty()) {
            result.error = e; // the first failing block's, whatever thread found it
            break;
        }
    return result;
}

EvalResult evaluate_image(const Graph& g, const std::string& output, EvalInputs inputs,
                          uint32_t width, uint32_t height, EvalPrecision precision) {
    // Lanes in 2x2 quads so derivatives see their neighbours; odd edges are padded.
    const uint32_t qw = (width + 1) / 2, qh = (height + 1) / 2;
    inputs.lanes = static_cast<size_t>(qw) * qh * 4;
    std::vector<double> uv(inputs.lanes * 2);
    for (uint32_t qy = 0; qy < qh; ++qy)
        for (uint32_t qx = 0; qx < qw; ++qx)
            for (uint32_t i = 0; i < 4; ++i) {
                const size_t lane = (static_cast<size_t>(qy) * qw + qx) * 4 + i;
                uv[lane * 2 + 0] = (2.0 * qx + (i & 1) + 0.5) / width;
                uv[lane * 2 + 1] = (2.0 * qy + (i >> 1) + 0.5) / height;
            }
    inputs.varyings["v_uv"] = std::move(uv);
    EvalResult quads = evaluate(g, output, inputs, precision);
    if (!quads.ok()) return quads;
    EvalResult image;
    image.components = quads.components;
    image.values.resize(static_cast<size_t>(width) * height * quads.components);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const size_t lane =
                (static_cast<size_t>(y / 2) * qw + x / 2) * 4 + (x & 1) + 2 * (y & 1);
            for (int c = 0; c < quads.components; ++c)
                image.values[(static_cast<size_t>(y) * width + x) * quads.components + c] =
                    quads.values[lane * quads.components + c];
        }
    return image;
}

} // namespace watergen
