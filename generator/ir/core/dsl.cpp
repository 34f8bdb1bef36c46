#include "watergen/ir/core/dsl.h"
#include "watergen/ir/core/op_table.h"

#include "dsl_internal.h"

#include <algorithm>
#include <vector>

namespace watergen {

namespace {

std::string types_of(const std::vector<Expr>& args) {
    std::string s;
    for (size_t i = 0; i < args.size(); ++i) {
        if (i) s += ", ";
        s += type_name(args[i].type());
    }
    return s;
}

// Type of `op` applied to `args`, or Type::Error with `why` filled in.
Type infer(Op op, const std::vector<Expr>& args, std::string& why) {
    auto t = [&](size_t i) { return args[i].type(); };
    auto same_float = [&](size_t first) {
        for (size_t i = first; i < args.size(); ++i)
            if (!is_float_numeric(t(i)) || t(i) != t(first)) return false;
        return true;
    };
    switch (op_info(op).typing) {
    case OpTyping::Arithmetic:
        if (t(0) == Type::Int && t(1) == Type::Int) return Type::Int;
        if (op == Op::Mul && t(0) == Type::Mat3 && t(1) == Type::Vec3) return Type::Vec3;
        if (is_float_numeric(t(0)) && is_float_numeric(t(1))) {
            if (t(0) == t(1)) return t(0);
            if (t(0) == Type::Float) return t(1);
            if (t(1) == Type::Float) return t(0);
        }
        why = "operand types differ";
        return Type::Error;
    case OpTyping::FloatUnary:
        if (is_float_numeric(t(0)) || (op == Op::Neg && t(0) == Type::Int)) return t(0);
        why = "expects a float scalar or vector";
        return Type::Error;
    case OpTyping::Compare:
        if (t(0) == t(1) && (t(0) == Type::Float || t(0) == Type::Int)) return Type::Bool;
        why = "compares two scalars of one type";
        return Type::Error;
    case OpTyping::Logic:
        if (t(0) == Type::Bool && t(1) == Type::Bool) return Type::Bool;
        why = "expects two bools";
        return Type::Error;
    case OpTyping::LogicNot:
        if (t(0) == Type::Bool) return Type::Bool;
        why = "expects a bool";
        return Type::Error;
    case OpTyping::Select:
        if (t(0) != Type::Bool) {
            why = "condition must be bool";
            return Type::Error;
        }
        if (t(1) == t(2) && t(1) != Type::Error) return t(1);
        why = "branches differ in type";
        return Type::Error;
    case OpTyping::Dot:
        if (same_float(0)) return Type::Float;
        why = "expects two float vectors of one size";
        return Type::Error;
    case OpTyping::Length:
        if (is_float_numeric(t(0))) return Type::Float;
        why = "expects a float vector";
        return Type::Error;
    case OpTyping::Cross:
        if (t(0) == Type::Vec3 && t(1) == Type::Vec3) return Type::Vec3;
        why = "expects two vec3";
        return Type::Error;
    case OpTyping::Reflect:
        if (same_float(0) && is_vector(t(0))) return t(0);
        why = "expects two float vectors of one size";
        return Type::Error;
    case OpTyping::Refract:
        if (is_vector(t(0)) && t(0) == t(1) && t(2) == Type::Float) return t(0);
        why = "expects (vecN incident, vecN normal, float eta)";
        return Type::Error;
    case OpTyping::SameFloat:
        if (same_float(0)) return t(0);
        why = "operand types differ";
        return Type::Error;
    case OpTyping::Sample:
        if (t(0) == Type::Texture2D && t(1) == Type::Vec2) return Type::Vec4;
        if (t(0) == Type::TextureCube && t(1) == Type::Vec3) return Type::Vec4;
        why = "expects (texture2D, vec2) or (textureCube, vec3)";
        return Type::Error;
    case OpTyping::SampleLevel:
        if (t(2) == Type::Float && ((t(0) == Type::Texture2D && t(1) == Type::Vec2) ||
                                    (t(0) == Type::TextureCube && t(1) == Type::Vec3)))
            return Type::Vec4;
        why = "expects (texture2D, vec2, float) or (textureCube, vec3, float)";
        return Type::Error;
    case OpTyping::Construct: {
        int n = 0;
        for (const auto& a : args) {
            if (!is_float_numeric(a.type())) {
                why = "components must be float scalars or vectors";
                return Type::Error;
            }
            n += component_count(a.type());
        }
        if (n >= 2 && n <= 4) return float_type(n);
        why = "makes a vector of 2 to 4 components, got " + std::to_string(n);
        return Type::Error;
    }
    case OpTyping::NotMade:
        break;
    }
    why = "is not built through make()";
    return Type::Error;
}

} // namespace

Expr error_expr(Graph& g) {
    Node n;
    n.op = Op::Constant;
    n.type = Type::Error;
    return Expr(&g, g.add(std::move(n)));
}

namespace {

// Whether `inner` is `outer` or a loop body being built inside it.
bool inside(const Graph* inner, const Graph* outer) {
    for (const Graph* g = inner; g; g = g->enclosing())
        if (g == outer) return true;
    return false;
}

} // namespace

Expr bring_into(Expr e, Graph& g) {
    if (!e.valid() || &e.graph() == &g) return e;
    if (!g.enclosing()) {
        e.graph().error("a value of one graph used in another that does not enclose it");
        return Expr();
    }
    Expr outer = bring_into(e, *g.enclosing());
    if (!outer.valid()) return outer;
    return Expr(&g, g.capture(outer.id()));
}

Expr make(Op op, std::initializer_list<Expr> list) {
    std::vector<Expr> args(list);
    // An argument no node produced (an axis that failed earlier) poisons the result; the
    // failure itself has been reported already.
    Graph* graph = nullptr;
    for (const auto& a : args)
        if (a.valid() && (!graph || inside(&a.graph(), graph))) graph = &a.graph();
    if (!graph) return Expr();
    Graph& g = *graph;
    // Values of enclosing code used in a loop body are captured into it.
    for (auto& a : args)
        if (a.valid() && &a.graph() != &g) a = bring_into(a, g);
    for (const auto& a : args)
        if (!a.valid()) return error_expr(g);
    const OpInfo& info = op_info(op);
    const int arity = info.arity;
    if (info.typing != OpTyping::NotMade && arity >= 0 && static_cast<int>(args.size()) != arity) {
        g.error(std::string(op_name(op)) + " expects " + std::to_string(arity) +
                " arguments, got " + std::to_string(args.size()));
        return error_expr(g);
    }
    for (const auto& a : args)
        if (a.type() == Type::Error) return error_expr(g); // already reported
    // GLSL and HLSL both broadcast scalars in arithmetic, but not uniformly in intrinsics:
    // make the broadcast explicit so every back end sees matching operand types.
    if (info.broadcast) {
        Type widest = Type::Float;
        const size_t first = op == Op::Select ? 1 : 0;
        for (size_t i = first; i < args.size(); ++i)
            if (is_vector(args[i].type())) widest = args[i].type();
        if (widest != Type::Float)
            for (size_t i = first; i < args.size(); ++i)
                if (args[i].type() == Type::Float) args[i] = splat(args[i], widest);
    }
    std::string why;
    const Type type = infer(op, args, why);
    if (type == Type::Error) {
        g.error(std::string(op_name(op)) + ": " + why + " (got " + types_of(args) + ")");
        return error_expr(g);
    }
    Node n;
    n.op = (op == Op::Mul && args[0].type() == Type::Mat3) ? Op::MatMulVec : op;
    n.type = type;
    for (const auto& a : args)
        n.args.push_back(a.id());
    return Expr(&g, g.add(std::move(n)));
}

Expr Expr::swizzle(std::string_view components) const {
    if (!g_) return *this;
    Graph& g = *g_;
    if (type() == Type::Error) return *this;
    const int available = component_count(type());
    if (!is_float_numeric(type()) || components.empty() || components.size() > 4) {
        g.error("swizzle '" + std::string(components) + "' of " + type_name(type()));
        return error_expr(g);
    }
    Node n;
    n.op = Op::Swizzle;
    n.type = float_type(static_cast<int>(components.size()));
    n.args = {id_};
    for (char c : components) {
        int idx = -1;
        switch (c) {
        case 'x':
        case 'r':
            idx = 0;
            break;
        case 'y':
        case 'g':
            idx = 1;
            break;
        case 'z':
        case 'b':
            idx = 2;
            break;
        case 'w':
        case 'a':
            idx = 3;
            break;
        default:
            break;
        }
        if (idx < 0 || idx >= available) {
            g.error("swizzle '" + std::string(components) + "' reads past a " + type_name(type()));
            return error_expr(g);
        }
        n.values.push_back(idx);
    }
    if (n.values.size() == static_cast<size_t>(available)) {
        bool identity = true;
        for (int i = 0; i < available; ++i)
            identity &= n.values[i] == i;
        if (identity) return *this;
    }
    return Expr(&g, g.add(std::move(n)));
}

Expr constant(Graph& g, double v) {
    return constant(g, {v});
}

Expr constant(Graph& g, std::initializer_list<double> components) {
    Node n;
    n.op = Op::Constant;
    n.type = float_type(static_cast<int>(components.size()));
    n.values.assign(components);
    if (n.type == Type::Error)
        g.error("constant with " + std::to_string(components.size()) + " components");
    return Expr(&g, g.add(std::move(n)));
}

Expr uniform(Graph& g, const Parameter& p) {
    // A loop body reads parameters and inputs through the enclosing code (Graph::capture).
    if (g.enclosing()) return bring_into(uniform(*g.enclosing(), p), g);
    g.declare_parameter(p);
    Node n;
    n.op = Op::Uniform;
    n.type = p.type;
    n.name = p.name;
    return Expr(&g, g.add(std::move(n)));
}

Expr element(const Parameter& array, Expr index) {
    if (!index.valid()) return index;
    Graph& g = index.graph(); // a loop body when the index is its LoopIndex
    if (array.array_size == 0) {
        g.error("element(): parameter '" + array.name + "' is not an array");
        return error_expr(g);
    }
    if (index.type() != Type::Float) {
        g.error("element(): index of '" + array.name + "' must be a float, got " +
                type_name(index.type()));
        return error_expr(g);
    }
    g.declare_parameter(array); // held by the outermost graph
    Node n;
    n.op = Op::UniformElement;
    n.type = array.type;
    n.name = array.name;
    n.args = {index.id()};
    return Expr(&g, g.add(std::move(n)));
}

Expr varying(Graph& g, const std::string& name, Type type) {
    if (g.enclosing()) return bring_into(varying(*g.enclosing(), name, type), g);
    Node n;
    n.op = Op::Varying;
    n.type = type;
    n.name = name;
    return Expr(&g, g.add(std::move(n)));
}

Expr texture(Graph& g, const TextureInput& t) {
    g.declare_texture(t);
    Node n;
    n.op = Op::Texture;
    n.type = t.type;
    n.name = t.name;
    return Expr(&g, g.add(std::move(n)));
}

Expr named(Expr e, const std::string& name) {
    if (!e.valid()) return e;
    Node copy = e.graph().node(e.id());
    if (is_leaf(copy.op) || copy.type == Type::Error || copy.type == Type::Tuple) return e;
    copy.name = name;
    return Expr(&e.graph(), e.graph().add(std::move(copy)));
}

Expr bind(const Quantity& quantity, Expr e) {
    if (!e.valid()) return e;
    Graph& g = e.graph();
    const Node& n = g.node(e.id());
    if (n.type == Type::Error) return e;
    const std::string id(quantity.id);
    if (n.type != quantity.type)
        g.error("quantity '" + id + "' is a " + type_name(quantity.type) + "; bound to a " +
                type_name(n.type));
    else if (!quantity.parameter.empty() && (n.op != Op::Uniform || n.name != quantity.parameter))
        g.error(
            "quantity '" + id + "' stands for parameter '" + std::string(quantity.parameter) +
            "'; bound to " +
            (n.op == Op::Uniform ? "parameter '" + n.name + "'" : std::string("a computed value")));
    else
        g.bind(quantity, e.id());
    return e;
}

} // namespace watergen
