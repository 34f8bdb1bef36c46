#include "watergen/ir/fold/interval.h"

#include <algorithm>
#include <cmath>

namespace watergen {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

// Relative widening per arithmetic operation (see the header).
double relative_margin(bool relaxed) {
    return relaxed ? 2e-3 : 1e-6;
}

// Product of two bounds where 0 x inf counts as 0: the values are finite, the infinite bound
// only says "no bound known".
double mul_bound(double a, double b) {
    if (a == 0.0 || b == 0.0) return 0.0;
    return a * b;
}

Interval finite_if(Interval r, bool args_finite, bool relaxed) {
    const double limit = largest_finite(relaxed);
    r.finite = args_finite && std::isfinite(r.lo) && std::isfinite(r.hi) &&
               std::fabs(r.lo) <= limit && std::fabs(r.hi) <= limit;
    return r;
}

Interval widen(Interval r, double rel, double abs = 0.0) {
    if (std::isfinite(r.lo)) r.lo -= std::fabs(r.lo) * rel + abs;
    if (std::isfinite(r.hi)) r.hi += std::fabs(r.hi) * rel + abs;
    return r;
}

Interval add(const Interval& a, const Interval& b) {
    return {a.lo + b.lo, a.hi + b.hi, a.finite && b.finite};
}
Interval sub(const Interval& a, const Interval& b) {
    return {a.lo - b.hi, a.hi - b.lo, a.finite && b.finite};
}
Interval neg(const Interval& a) {
    return {-a.hi, -a.lo, a.finite};
}

Interval mul(const Interval& a, const Interval& b) {
    const double p[4] = {mul_bound(a.lo, b.lo), mul_bound(a.lo, b.hi), mul_bound(a.hi, b.lo),
                         mul_bound(a.hi, b.hi)};
    return {*std::min_element(p, p + 4), *std::max_element(p, p + 4), a.finite && b.finite};
}

Interval div(const Interval& a, const Interval& b) {
    if (b.lo <= 0.0 && b.hi >= 0.0) return {-kInf, kInf, false};
    const Interval inv{1.0 / b.hi, 1.0 / b.lo, b.finite};
    return mul(a, inv);
}

Interval hull(const Interval& a, const Interval& b) {
    return {std::min(a.lo, b.lo), std::max(a.hi, b.hi), a.finite && b.finite};
}

Interval square(const Interval& a) {
    const double l = a.lo * a.lo, h = a.hi * a.hi;
    if (a.lo <= 0.0 && a.hi >= 0.0) return {0.0, std::max(l, h), a.finite};
    return {std::min(l, h), std::max(l, h), a.finite};
}

Interval imin(const Interval& a, const Interval& b) {
    return {std::min(a.lo, b.lo), std::min(a.hi, b.hi), a.finite && b.finite};
}
Interval imax(const Interval& a, const Interval& b) {
    return {std::max(a.lo, b.lo), std::max(a.hi, b.hi), a.finite && b.finite};
}

Interval monotone(const Interval& a, double (*f)(double)) {
    return {f(a.lo), f(a.hi), a.finite};
}

double magnitude(const Interval& a) {
    return std::max(std::fabs(a.lo), std::fabs(a.hi));
}

Interval bool_interval(bool decided, bool value) {
    if (!decided) return {0.0, 1.0, true};
    return value ? Interval{1.0, 1.0, true} : Interval{0.0, 0.0, true};
}

} // namespace

double largest_finite(bool relaxed) {
    return relaxed ? 65504.0 : 3.4028234663852886e38;
}

Interval make_interval(double lo, double hi) {
    return {lo, hi, std::isfinite(lo) && std::isfinite(hi)};
}

Intervals unknown_intervals(Type t, bool finite) {
    return Intervals(static_cast<size_t>(std::max(component_count(t), 0)),
                     Interval{-kInf, kInf, finite});
}

bool decided_true(const Intervals& v) {
    return v.size() == 1 && v[0].lo == 1.0 && v[0].hi == 1.0;
}
bool decided_false(const Intervals& v) {
    return v.size() == 1 && v[0].lo == 0.0 && v[0].hi == 0.0;
}

Intervals node_intervals(const Node& n, const std::vector<const Intervals*>& args,
                         const std::vector<Type>& arg_types) {
    const int comps = std::max(component_count(n.type), 0);
    const bool relaxed = n.relaxed;
    const double rel = relative_margin(relaxed);
    Intervals out(static_cast<size_t>(comps));
    // Component c of argument i, broadcasting scalars.
    auto a = [&](size_t i, int c) -> const Interval& {
        const Intervals& v = *args[i];
        return v.size() == 1 ? v[0] : v[static_cast<size_t>(c)];
    };
    auto each = [&](auto f) {
        for (int c = 0; c < comps; ++c)
            out[static_cast<size_t>(c)] = f(c);
    };
    // Arithmetic: widened for rounding, finite only within the precision's range.
    auto arith = [&](auto f, double r = -1.0, double abs = 0.0) {
        each([&](int c) {
            const Interval v = f(c);
            return finite_if(widen(v, r < 0 ? rel : std::max(r, rel), abs), v.finite, relaxed);
        });
    };
    // Exact selections (min, max, clamp, ...): no rounding, same range as the arguments.
    auto exact = [&](auto f) {
        each([&](int c) {
            const Interval v = f(c);
            return finite_if(v, v.finite, relaxed);
        });
    };
    auto reduce = [&](size_t i, size_t j) {
        const int k = component_count(arg_types[i]);
        Interval s{0.0, 0.0, true};
        for (int c = 0; c < k; ++c)
            s = add(s, mul(a(i, c), a(j, c)));
        return s;
    };
    auto sum_squares = [&](size_t i) {
        const int k = component_count(arg_types[i]);
        Interval s{0.0, 0.0, true};
        for (int c = 0; c < k; ++c)
            s = add(s, square(a(i, c)));
        return s;
    };

    switch (n.op) {
    case Op::Constant:
        each([&](int c) {
            const double v =
                static_cast<size_t>(c) < n.values.size() ? n.values[static_cast<size_t>(c)] : 0.0;
            return make_interval(v, v);
        });
        return out;
    case Op::Uniform:
    case Op::UniformElement:
    case Op::Varying:
    case Op::Texture:
    case Op::Sample:
    case Op::SampleLevel:
        return unknown_intervals(n.type, false);
    // Loops: no bound here; the fold pass iterates the body's bounds (loop_bounds.cpp), and a
    // body's leaves are as unknown as the values they stand for.
    case Op::Loop:
    case Op::LoopResult:
    case Op::LoopIndex:
    case Op::Carried:
    case Op::Captured:
        return unknown_intervals(n.type, false);
    // A switch's results need its cases: switch_result_intervals().
    case Op::Switch:
    case Op::SwitchResult:
        return unknown_intervals(n.type, false);
    case Op::Add:
        arith([&](int c) { return add(a(0, c), a(1, c)); });
        return out;
    case Op::Sub:
        arith([&](int c) { return sub(a(0, c), a(1, c)); });
        return out;
    case Op::Mul:
        arith([&](int c) { return mul(a(0, c), a(1, c)); });
        return out;
    case Op::Div:
        arith([&](int c) { return div(a(0, c), a(1, c)); });
        return out;
    case Op::Neg:
        exact([&](int c) { return neg(a(0, c)); });
        return out;
    case Op::Less:
    case Op::LessEqual:
    case Op::Greater:
    case Op::GreaterEqual:
    case Op::Equal:
    case Op::NotEqual: {
        const Interval& x = a(0, 0);
        const Interval& y = a(1, 0);
        bool decided = x.finite && y.finite, value = false;
        switch (n.op) {
        case Op::Less:
            value = x.hi < y.lo;
            decided = decided && (x.hi < y.lo || x.lo >= y.hi);
            break;
        case Op::LessEqual:
            value = x.hi <= y.lo;
            decided = decided && (x.hi <= y.lo || x.lo > y.hi);
            break;
        case Op::Greater:
            value = x.lo > y.hi;
            decided = decided && (x.lo > y.hi || x.hi <= y.lo);
            break;
        case Op::GreaterEqual:
            value = x.lo >= y.hi;
            decided = decided && (x.lo >= y.hi || x.hi < y.lo);
            break;
        case Op::Equal:
        case Op::NotEqual: {
            const bool same = x.is_point() && y.is_point() && x.lo == y.lo;
            const bool apart = x.hi < y.lo || y.hi < x.lo;
            decided = decided && (same || apart);
            value = (n.op == Op::Equal) == same;
            break;
        }
        default:
            break;
        }
        out[0] = bool_interval(decided, value);
        return out;
    }
    case Op::And:
        if (decided_false(*args[0]) || decided_false(*args[1]))
            out[0] = bool_interval(true, false);
        else
            out[0] = bool_interval(decided_true(*args[0]) && decided_true(*args[1]), true);
        return out;
    case Op::Or:
        if (decided_true(*args[0]) || decided_true(*args[1]))
            out[0] = bool_interval(true, true);
        else
            out[0] = bool_interval(decided_false(*args[0]) && decided_false(*args[1]), false);
        return out;
    case Op::Not:
        out[0] = bool_interval(decided_true(*args[0]) || decided_false(*args[0]),
                               decided_false(*args[0]));
        return out;
    case Op::Select:
        if (decided_true(*args[0]))
            exact([&](int c) { return a(1, c); });
        else if (decided_false(*args[0]))
            exact([&](int c) { return a(2, c); });
        else
            exact([&](int c) { return hull(a(1, c), a(2, c)); });
        return out;
    case Op::Swizzle:
        each([&](int c) { return a(0, static_cast<int>(n.values[static_cast<size_t>(c)])); });
        return out;
    case Op::Splat:
        each([&](int) { return a(0, 0); });
        return out;
    case Op::Construct: {
        size_t c = 0;
        for (size_t i = 0; i < args.size(); ++i)
            for (const Interval& v : *args[i])
                if (c < out.size()) out[c++] = v;
        return out;
    }
    case Op::Dot:
        arith([&](int) { return reduce(0, 1); });
        return out;
    case Op::Length:
        arith([&](int) {
            const Interval s = sum_squares(0);
            return Interval{std::sqrt(std::max(s.lo, 0.0)), std::sqrt(s.hi), s.finite};
        });
        return out;
    case Op::Normalize: {
        const Interval s = sum_squares(0);
        arith([&](int) { return Interval{-1.0, 1.0, s.finite && s.lo > 0.0}; });
        return out;
    }
    case Op::Cross:
        arith([&](int c) {
            const int i = (c + 1) % 3, j = (c + 2) % 3;
            return sub(mul(a(0, i), a(1, j)), mul(a(0, j), a(1, i)));
        });
        return out;
    case Op::Mix:
        arith([&](int c) { return add(a(0, c), mul(sub(a(1, c), a(0, c)), a(2, c))); });
        return out;
    case Op::Clamp:
        exact([&](int c) { return imin(imax(a(0, c), a(1, c)), a(2, c)); });
        return out;
    case Op::Saturate:
        exact([&](int c) {
            const Interval& x = a(0, c);
            return Interval{std::clamp(x.lo, 0.0, 1.0), std::clamp(x.hi, 0.0, 1.0), x.finite};
        });
        return out;
    case Op::Min:
        exact([&](int c) { return imin(a(0, c), a(1, c)); });
        return out;
    case Op::Max:
        exact([&](int c) { return imax(a(0, c), a(1, c)); });
        return out;
    case Op::Pow:
        arith(
            [&](int c) {
                const Interval& x = a(0, c);
                const Interval& y = a(1, c);
                if (!(x.lo > 0.0 || (x.lo >= 0.0 && y.lo > 0.0)))
                    return Interval{-kInf, kInf, false};
                const double p[4] = {std::pow(x.lo, y.lo), std::pow(x.lo, y.hi),
                                     std::pow(x.hi, y.lo), std::pow(x.hi, y.hi)};
                return Interval{*std::min_element(p, p + 4), *std::max_element(p, p + 4),
                                x.finite && y.finite};
            },
            1e-4);
        return out;
    case Op::Exp:
    case Op::Exp2: {
        const bool e = n.op == Op::Exp;
        arith([&](int c) {
            const Interval& x = a(0, c);
            return Interval{e ? std::exp(x.lo) : std::exp2(x.lo),
                            e ? std::exp(x.hi) : std::exp2(x.hi), x.finite};
        });
        return out;
    }
    case Op::Log:
        arith(
            [&](int c) {
                const Interval& x = a(0, c);
                if (!(x.lo > 0.0)) return Interval{-kInf, kInf, false};
                return Interval{std::log(x.lo), std::log(x.hi), x.finite};
            },
            -1.0, 1e-6);
        return out;
    case Op::Sqrt:
        arith([&](int c) {
            const Interval& x = a(0, c);
            return Interval{std::sqrt(std::max(x.lo, 0.0)), std::sqrt(std::max(x.hi, 0.0)),
                            x.finite && x.lo >= 0.0};
        });
        return out;
    case Op::Rsqrt:
        arith([&](int c) {
            const Interval& x = a(0, c);
            if (!(x.lo > 0.0)) return Interval{0.0, kInf, false};
            return Interval{1.0 / std::sqrt(x.hi), 1.0 / std::sqrt(x.lo), x.finite};
        });
        return out;
    case Op::Abs:
        exact([&](int c) {
            const Interval& x = a(0, c);
            if (x.lo >= 0.0) return x;
            if (x.hi <= 0.0) return neg(x);
            return Interval{0.0, std::max(-x.lo, x.hi), x.finite};
        });
        return out;
    case Op::Sign:
        exact([&](int c) {
            const Interval& x = a(0, c);
            const double lo = x.lo > 0.0 ? 1.0 : x.lo >= 0.0 ? 0.0 : -1.0;
            const double hi = x.hi < 0.0 ? -1.0 : x.hi <= 0.0 ? 0.0 : 1.0;
            return Interval{lo, hi, x.finite};
        });
        return out;
    case Op::Sin:
    case Op::Cos:
        arith([&](int c) { return Interval{-1.0, 1.0, a(0, c).finite}; }, -1.0, 1e-3);
        return out;
    case Op::Atan2:
        arith(
            [&](int c) {
                const Interval& y = a(0, c);
                const Interval& x = a(1, c);
                const bool defined = !(y.lo <= 0.0 && y.hi >= 0.0 && x.lo <= 0.0 && x.hi >= 0.0);
                return Interval{-kPi, kPi, x.finite && y.finite && defined};
            },
            -1.0, 1e-3);
        return out;
    case Op::Reflect:
        arith([&](int c) {
            const Interval d = reduce(1, 0);
            return sub(a(0, c), mul(mul(Interval{2.0, 2.0, true}, d), a(1, c)));
        });
        return out;
    case Op::Refract: {
        // |eta I - (eta dot + sqrt(k)) N| per component, with k <= 1 + eta^2 dot^2; or 0.
        const Interval d = reduce(1, 0);
        const double e = magnitude(a(2, 0)), dm = magnitude(d);
        double im = 0.0, nm = 0.0;
        bool f = a(2, 0).finite && d.finite;
        for (int c = 0; c < comps; ++c) {
            im = std::max(im, magnitude(a(0, c)));
            nm = std::max(nm, magnitude(a(1, c)));
            f = f && a(0, c).finite && a(1, c).finite;
        }
        const double bound = e * im + (e * dm + std::sqrt(1.0 + e * e * dm * dm)) * nm;
        arith([&](int) { return Interval{-bound, bound, f}; });
        return out;
    }
    case Op::Step:
        exact([&](int c) {
            const Interval& edge = a(0, c);
            const Interval& x = a(1, c);
            if (x.lo >= edge.hi) return Interval{1.0, 1.0, x.finite && edge.finite};
            if (x.hi < edge.lo) return Interval{0.0, 0.0, x.finite && edge.finite};
            return Interval{0.0, 1.0, x.finite && edge.finite};
        });
        return out;
    case Op::Smoothstep:
        arith([&](int c) {
            const Interval& e0 = a(0, c);
            const Interval& e1 = a(1, c);
            const Interval& x = a(2, c);
            const Interval span = sub(e1, e0);
            const bool ok = e0.finite && e1.finite && x.finite && (span.lo > 0.0 || span.hi < 0.0);
            if (ok && e0.hi < e1.lo && x.lo >= e1.hi) return Interval{1.0, 1.0, true};
            if (ok && e0.hi < e1.lo && x.hi <= e0.lo) return Interval{0.0, 0.0, true};
            return Interval{0.0, 1.0, ok};
        });
        return out;
    case Op::Fract:
        arith([&](int c) {
            const Interval& x = a(0, c);
            if (x.finite && std::floor(x.lo) == std::floor(x.hi))
                return Interval{x.lo - std::floor(x.lo), x.hi - std::floor(x.hi), true};
            return Interval{0.0, 1.0, x.finite};
        });
        return out;
    case Op::Floor:
        exact([&](int c) { return monotone(a(0, c), [](double v) { return std::floor(v); }); });
        return out;
    case Op::Mod:
        arith([&](int c) {
            const Interval& y = a(1, c);
            const bool f = a(0, c).finite && y.finite;
            if (y.lo > 0.0) return Interval{0.0, y.hi, f};
            if (y.hi < 0.0) return Interval{y.lo, 0.0, f};
            return Interval{-kInf, kInf, false};
        });
        return out;
    case Op::MatMulVec:
        arith([&](int r) {
            Interval s{0.0, 0.0, true};
            for (int k = 0; k < 3; ++k)
                s = add(s, mul(a(0, k * 3 + r), a(1, k)));
            return s;
        });
        return out;
    case Op::Ddx:
    case Op::Ddy:
        arith([&](int c) {
            const Interval& x = a(0, c);
            if (x.is_point()) return Interval{0.0, 0.0, true};
            return Interval{x.lo - x.hi, x.hi - x.lo, x.finite};
        });
        return out;
    }
    return unknown_intervals(n.type, false);
}

Intervals switch_result_intervals(const Node& sw, size_t k,
                                  const std::vector<const Intervals*>& args) {
    const SwitchCases& cases = *sw.cases;
    const Interval& selector = (*args[0])[0];
    Intervals out;
    for (size_t c = 0; c < cases.cases.size(); ++c) {
        if (selector.is_point() && cases.case_for(selector.lo) != c) continue;
        const Graph& body = *cases.cases[c];
        std::vector<Intervals> values(body.size());
        for (uint32_t id : body.live_nodes()) {
            const Node& n = body.node(id);
            if (n.op == Op::Captured) {
                values[id] = *args[cases.case_args[c] + static_cast<size_t>(n.values[0])];
                continue;
            }
            std::vector<const Intervals*> in;
            std::vector<Type> types;
            for (uint32_t a : n.args) {
                in.push_back(&values[a]);
                types.push_back(body.node(a).type);
            }
            values[id] = node_intervals(n, in, types);
        }
        const Intervals& result = values[body.outputs()[k].node];
        if (out.empty()) {
            out = result;
            continue;
        }
        for (size_t i = 0; i < out.size() && i < result.size(); ++i)
            out[i] = hull(out[i], result[i]);
    }
    return out;
}

} // namespace watergen
