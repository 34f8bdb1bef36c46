// The C++ DSL feature nodes are written in. An Expr is a handle to a node of a Graph;
// operators and intrinsics check types when the description is built and record a diagnostic
// naming the feature node on a mismatch (vec3 + vec2, wrong arity), never leaving it to glslang.
//
//   OriginScope scope(g, "fresnel.schlick");
//   Expr r0 = named(square((n1 - n2) / (n1 + n2)), "r0");
//   Expr f = r0 + (1.0 - r0) * pow(1.0 - c, 5.0);
#pragma once

#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "watergen/ir/core/ir.h"

namespace watergen {

class Expr {
  public:
    Expr() = default;
    Expr(Graph* g, uint32_t id) : g_(g), id_(id) {}

    Graph& graph() const { return *g_; }
    uint32_t id() const { return id_; }
    Type type() const { return g_ ? g_->node(id_).type : Type::Error; }
    bool valid() const { return g_ != nullptr; }

    // Swizzles, GLSL letters xyzw / rgba: e.swizzle("xz").
    Expr swizzle(std::string_view components) const;
    Expr x() const { return swizzle("x"); }
    Expr y() const { return swizzle("y"); }
    Expr z() const { return swizzle("z"); }
    Expr w() const { return swizzle("w"); }
    Expr xy() const { return swizzle("xy"); }
    Expr xz() const { return swizzle("xz"); }
    Expr xyz() const { return swizzle("xyz"); }

  private:
    Graph* g_ = nullptr;
    uint32_t id_ = 0;
};

// Sets the graph's current feature node for the lifetime of the scope.
class OriginScope {
  public:
    OriginScope(Graph& g, std::string origin) : g_(g), previous_(g.origin()) {
        g.set_origin(std::move(origin));
    }
    ~OriginScope() { g_.set_origin(previous_); }
    OriginScope(const OriginScope&) = delete;
    OriginScope& operator=(const OriginScope&) = delete;

  private:
    Graph& g_;
    std::string previous_;
};

// Sets the author of what a registered node declares and reports (ir.h, Author) while alive.
class AuthorScope {
  public:
    AuthorScope(Graph& g, Author author) : g_(g), previous_(g.author()) {
        g.set_author(std::move(author));
    }
    ~AuthorScope() { g_.set_author(previous_); }
    AuthorScope(const AuthorScope&) = delete;
    AuthorScope& operator=(const AuthorScope&) = delete;

  private:
    Graph& g_;
    Author previous_;
};

// Marks subsequent operations relaxed precision (mediump / min16float) when `relaxed`.
class RelaxedScope {
  public:
    RelaxedScope(Graph& g, bool relaxed) : g_(g), previous_(g.relaxed()) {
        g.set_relaxed(relaxed || previous_);
    }
    ~RelaxedScope() { g_.set_relaxed(previous_); }
    RelaxedScope(const RelaxedScope&) = delete;
    RelaxedScope& operator=(const RelaxedScope&) = delete;

  private:
    Graph& g_;
    bool previous_;
};

// Forces 32-bit operations for its lifetime whatever the enclosing RelaxedScope says: geometry
// (positions up to 1e5 m, times up to a day) overflows or loses all precision in binary16.
class FullPrecisionScope {
  public:
    explicit FullPrecisionScope(Graph& g) : g_(g), previous_(g.relaxed()) { g.set_relaxed(false); }
    ~FullPrecisionScope() { g_.set_relaxed(previous_); }
    FullPrecisionScope(const FullPrecisionScope&) = delete;
    FullPrecisionScope& operator=(const FullPrecisionScope&) = delete;

  private:
    Graph& g_;
    bool previous_;
};

// Leaves.
Expr constant(Graph& g, double v);
Expr constant(Graph& g, std::initializer_list<double> components);
Expr uniform(Graph& g, const Parameter& p); // declares p and reads it
// Element floor(index), clamped to [0, array_size - 1], of an array parameter (declares it);
// in a loop body the index is typically the loop index. Arrays are never specialization constants.
Expr element(const Parameter& array, Expr index);
Expr varying(Graph& g, const std::string& name, Type type);
Expr texture(Graph& g, const TextureInput& t);

// Gives the emitted temporary a readable name.
Expr named(Expr e, const std::string& name);

// Binds `e` to `quantity` (Graph::bind) and returns it. A type other than the quantity's, or
// a quantity that stands for a parameter bound to anything but the uniform of that name,
// records a diagnostic: a renamed uniform fails to compose instead of losing its facts.
Expr bind(const Quantity& quantity, Expr e);

// Generic node construction with type checking; used by everything below.
Expr make(Op op, std::initializer_list<Expr> args);

Expr operator+(Expr a, Expr b);
Expr operator-(Expr a, Expr b);
Expr operator*(Expr a, Expr b);
Expr operator/(Expr a, Expr b);
Expr operator-(Expr a);
Expr operator+(Expr a, double b);
Expr operator+(double a, Expr b);
Expr operator-(Expr a, double b);
Expr operator-(double a, Expr b);
Expr operator*(Expr a, double b);
Expr operator*(double a, Expr b);
Expr operator/(Expr a, double b);
Expr operator/(double a, Expr b);

Expr operator<(Expr a, Expr b);
Expr operator<=(Expr a, Expr b);
Expr operator>(Expr a, Expr b);
Expr operator>=(Expr a, Expr b);
Expr operator<(Expr a, double b);
Expr operator<=(Expr a, double b);
Expr operator>(Expr a, double b);
Expr operator>=(Expr a, double b);
Expr operator&&(Expr a, Expr b);
Expr operator||(Expr a, Expr b);
Expr operator!(Expr a);

Expr select(Expr condition, Expr if_true, Expr if_false);
Expr vec2(Expr a, Expr b);
Expr vec3(Expr a, Expr b, Expr c);
Expr vec3(Expr xy, Expr z);
Expr vec4(Expr xyz, Expr w);
Expr vec4(Expr a, Expr b, Expr c, Expr d);
Expr mat3(Expr c0, Expr c1, Expr c2); // columns
Expr splat(Expr scalar, Type vector_type);

Expr dot(Expr a, Expr b);
Expr cross(Expr a, Expr b);
Expr normalize(Expr a);
Expr length(Expr a);
Expr mix(Expr a, Expr b, Expr t);
Expr mix(Expr a, Expr b, double t);
Expr clamp(Expr x, Expr lo, Expr hi);
Expr clamp(Expr x, double lo, double hi);
Expr saturate(Expr x);
Expr pow(Expr x, Expr y);
Expr pow(Expr x, double y);
Expr exp(Expr x);
Expr exp2(Expr x);
Expr log(Expr x);
Expr sqrt(Expr x);
Expr rsqrt(Expr x);
Expr abs(Expr x);
Expr sign(Expr x);
Expr min(Expr a, Expr b);
Expr max(Expr a, Expr b);
Expr min(Expr a, double b);
Expr max(Expr a, double b);
Expr sin(Expr x);
Expr cos(Expr x);
Expr atan2(Expr y, Expr x);
Expr reflect(Expr incident, Expr normal);
Expr refract(Expr incident, Expr normal, Expr eta);
Expr step(Expr edge, Expr x);
Expr smoothstep(Expr edge0, Expr edge1, Expr x);
Expr fract(Expr x);
Expr floor(Expr x);
Expr mod(Expr x, Expr y);
Expr square(Expr x);
Expr sample(Expr texture, Expr coordinate);
Expr sample_level(Expr texture, Expr coordinate, Expr lod);
Expr ddx(Expr x);
Expr ddy(Expr x);

// Bounded loops. A body is written like any other code: it gets the iteration (0, 1, ... as a
// float) and the carried values at the iteration's start, may read any value of the enclosing
// code (computed once, outside the loop, and captured), and returns the carried values of the
// next iteration plus, optionally, a Bool that ends the loop where it is false (after the
// carried values are updated). Emitted as a real `for` loop in GLSL and HLSL; the CPU
// evaluator runs it per pixel. Bodies may not take ddx / ddy, nor (with an exit) sample with
// implicit LOD: both are undefined in non-uniform control flow.
struct LoopStep {
    std::vector<Expr> next;
    Expr keep_going; // optional
};
struct LoopOptions {
    UnrollHint unroll = UnrollHint::Keep; // the compiler hint
};
using LoopBodyFn = std::function<LoopStep(Expr index, const std::vector<Expr>& carried)>;
// The carried values after at most `trip_count` iterations (1..4096), typed like `initial`.
// The loop runs in `g`, or in the innermost loop body being built that an initial value (or the
// count) belongs to: a loop nested in another's body whose initial values are all outer values
// is given that body's graph as `g` (the graph of any value of the body, e.g. `xz.graph()`).
std::vector<Expr> loop(Graph& g, int trip_count, const std::vector<Expr>& initial,
                       const LoopBodyFn& body, LoopOptions options = {});
// A trip count from data: `count` (float) runs min(floor(count), max_trip_count) iterations,
// none where floor(count) < 1 or count is NaN (the initial values come out); max_trip_count is
// 1..4096. Every pixel runs the same count: `count` may read parameters (uniforms or
// specialization constants) and constants only; a varying, texture, loop index, carried value or
// loop result in it is a diagnostic. Emitted as `for (i = 0; i < max; ++i) { if (!(float(i) <
// floor(count))) break; ... }`.
std::vector<Expr> loop(Graph& g, Expr count, int max_trip_count, const std::vector<Expr>& initial,
                       const LoopBodyFn& body, LoopOptions options = {});

// Uniform choices. choose() builds one graph per case, like a loop body: case_body gets the
// case's graph and index and returns the results, and may read any value of the enclosing code
// (captured; read_in() captures one explicitly, so that everything computed from it is the
// case's own work). The selector must be the same on every pixel of a draw: a Float built from
// constants and parameters only (a specialization constant or a uniform-block member). Case k
// runs where the selector is k, the last case for any other value; it is emitted as
// `if (sel == 0.0) {...} else if ...`, so the other cases do not run, and cases may take
// derivatives. Every case gives the same number of results, typed alike; a result no case gives
// (an invalid Expr in every case) comes back invalid, one some cases give and others do not is
// an error unless fill_missing supplies it. A result every case passes through unchanged is the
// outer value itself. A quantity every case binds to its result k (Graph::bind) is bound to result
// k. fill_missing, when given, supplies a result some cases give and another does not, in that
// case's graph (result index and type); an invalid Expr from it leaves the error.
using CaseFn = std::function<std::vector<Expr>(Graph& case_graph, int case_index)>;
using FillFn = std::function<Expr(Graph& case_graph, size_t result, Type type)>;
std::vector<Expr> choose(Graph& g, Expr selector, int cases, const CaseFn& case_body,
                         const FillFn& fill_missing = {});
// `outer` as a value of `body`, a loop body or case being built inside its graph (captured).
Expr read_in(Graph& body, Expr outer);

} // namespace watergen
