// The DSL's vocabulary: operators and intrinsics, each one node of the IR (types checked by
// make(), dsl.cpp).
#include "watergen/ir/core/dsl.h"

#include "dsl_internal.h"

#include <cmath>

namespace watergen {

namespace {
Expr c(Expr like, double v) {
    return like.valid() ? constant(like.graph(), v) : Expr();
}
} // namespace

Expr operator+(Expr a, Expr b) {
    return make(Op::Add, {a, b});
}
Expr operator-(Expr a, Expr b) {
    return make(Op::Sub, {a, b});
}
Expr operator*(Expr a, Expr b) {
    return make(Op::Mul, {a, b});
}
Expr operator/(Expr a, Expr b) {
    return make(Op::Div, {a, b});
}
Expr operator-(Expr a) {
    return make(Op::Neg, {a});
}
Expr operator+(Expr a, double b) {
    return a + c(a, b);
}
Expr operator+(double a, Expr b) {
    return c(b, a) + b;
}
Expr operator-(Expr a, double b) {
    return a - c(a, b);
}
Expr operator-(double a, Expr b) {
    return c(b, a) - b;
}
Expr operator*(Expr a, double b) {
    return a * c(a, b);
}
Expr operator*(double a, Expr b) {
    return c(b, a) * b;
}
Expr operator/(Expr a, double b) {
    return a / c(a, b);
}
Expr operator/(double a, Expr b) {
    return c(b, a) / b;
}

Expr operator<(Expr a, Expr b) {
    return make(Op::Less, {a, b});
}
Expr operator<=(Expr a, Expr b) {
    return make(Op::LessEqual, {a, b});
}
Expr operator>(Expr a, Expr b) {
    return make(Op::Greater, {a, b});
}
Expr operator>=(Expr a, Expr b) {
    return make(Op::GreaterEqual, {a, b});
}
Expr operator<(Expr a, double b) {
    return a < c(a, b);
}
Expr operator<=(Expr a, double b) {
    return a <= c(a, b);
}
Expr operator>(Expr a, double b) {
    return a > c(a, b);
}
Expr operator>=(Expr a, double b) {
    return a >= c(a, b);
}
Expr operator&&(Expr a, Expr b) {
    return make(Op::And, {a, b});
}
Expr operator||(Expr a, Expr b) {
    return make(Op::Or, {a, b});
}
Expr operator!(Expr a) {
    return make(Op::Not, {a});
}

Expr select(Expr condition, Expr if_true, Expr if_false) {
    return make(Op::Select, {condition, if_true, if_false});
}
Expr vec2(Expr a, Expr b) {
    return make(Op::Construct, {a, b});
}
Expr vec3(Expr a, Expr b, Expr c3) {
    return make(Op::Construct, {a, b, c3});
}
Expr vec3(Expr xy, Expr z) {
    return make(Op::Construct, {xy, z});
}
Expr vec4(Expr xyz, Expr w) {
    return make(Op::Construct, {xyz, w});
}
Expr vec4(Expr a, Expr b, Expr c3, Expr d) {
    return make(Op::Construct, {a, b, c3, d});
}

Expr mat3(Expr c0, Expr c1, Expr c2) {
    if (!c0.valid()) return make(Op::Construct, {c0, c1, c2});
    Graph& g = c0.graph();
    for (const Expr& col : {c0, c1, c2}) {
        if (col.type() == Type::Error) return error_expr(g);
        if (col.type() != Type::Vec3) {
            g.error(std::string("mat3: columns must be vec3 (got ") + type_name(col.type()) + ")");
            return error_expr(g);
        }
    }
    Node n;
    n.op = Op::Construct;
    n.type = Type::Mat3;
    n.args = {c0.id(), c1.id(), c2.id()};
    return Expr(&g, g.add(std::move(n)));
}

Expr splat(Expr scalar, Type vector_type) {
    if (!scalar.valid()) return scalar;
    Graph& g = scalar.graph();
    if (scalar.type() == Type::Error) return scalar;
    if (scalar.type() != Type::Float || !is_vector(vector_type)) {
        g.error(std::string("splat: needs a float and a vector type (got ") +
                type_name(scalar.type()) + ")");
        return error_expr(g);
    }
    Node n;
    n.op = Op::Splat;
    n.type = vector_type;
    n.args = {scalar.id()};
    return Expr(&g, g.add(std::move(n)));
}

Expr dot(Expr a, Expr b) {
    return make(Op::Dot, {a, b});
}
Expr cross(Expr a, Expr b) {
    return make(Op::Cross, {a, b});
}
Expr normalize(Expr a) {
    return make(Op::Normalize, {a});
}
Expr length(Expr a) {
    return make(Op::Length, {a});
}
Expr mix(Expr a, Expr b, Expr t) {
    return make(Op::Mix, {a, b, t});
}
Expr mix(Expr a, Expr b, double t) {
    return mix(a, b, c(a, t));
}
Expr clamp(Expr x, Expr lo, Expr hi) {
    return make(Op::Clamp, {x, lo, hi});
}
Expr clamp(Expr x, double lo, double hi) {
    return clamp(x, c(x, lo), c(x, hi));
}
Expr saturate(Expr x) {
    return make(Op::Saturate, {x});
}
Expr pow(Expr x, Expr y) {
    return make(Op::Pow, {x, y});
}
Expr pow(Expr x, double y) {
    return pow(x, c(x, y));
}
Expr exp(Expr x) {
    return make(Op::Exp, {x});
}
Expr exp2(Expr x) {
    return make(Op::Exp2, {x});
}
Expr log(Expr x) {
    return make(Op::Log, {x});
}
Expr sqrt(Expr x) {
    return make(Op::Sqrt, {x});
}
Expr rsqrt(Expr x) {
    return make(Op::Rsqrt, {x});
}
Expr abs(Expr x) {
    return make(Op::Abs, {x});
}
Expr sign(Expr x) {
    return make(Op::Sign, {x});
}
Expr min(Expr a, Expr b) {
    return make(Op::Min, {a, b});
}
Expr max(Expr a, Expr b) {
    return make(Op::Max, {a, b});
}
Expr min(Expr a, double b) {
    return min(a, c(a, b));
}
Expr max(Expr a, double b) {
    return max(a, c(a, b));
}
Expr sin(Expr x) {
    return make(Op::Sin, {x});
}
Expr cos(Expr x) {
    return make(Op::Cos, {x});
}
Expr atan2(Expr y, Expr x) {
    return make(Op::Atan2, {y, x});
}
Expr reflect(Expr incident, Expr normal) {
    return make(Op::Reflect, {incident, normal});
}
Expr refract(Expr incident, Expr normal, Expr eta) {
    return make(Op::Refract, {incident, normal, eta});
}
Expr step(Expr edge, Expr x) {
    return make(Op::Step, {edge, x});
}
Expr smoothstep(Expr e0, Expr e1, Expr x) {
    return make(Op::Smoothstep, {e0, e1, x});
}
Expr fract(Expr x) {
    return make(Op::Fract, {x});
}
Expr floor(Expr x) {
    return make(Op::Floor, {x});
}
Expr mod(Expr x, Expr y) {
    return make(Op::Mod, {x, y});
}
Expr square(Expr x) {
    return x * x;
}
Expr sample(Expr tex, Expr coordinate) {
    return make(Op::Sample, {tex, coordinate});
}
Expr sample_level(Expr tex, Expr coordinate, Expr lod) {
    return make(Op::SampleLevel, {tex, coordinate, lod});
}
Expr ddx(Expr x) {
    return make(Op::Ddx, {x});
}
Expr ddy(Expr x) {
    return make(Op::Ddy, {x});
}

} // namespace watergen
