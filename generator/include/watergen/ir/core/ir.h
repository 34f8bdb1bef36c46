// The typed expression IR every back end reads: a hash-consed DAG of pure operations.
// Node math is written once against this IR (see dsl.h); the GLSL emitter, the HLSL emitter
// and the CPU evaluator are its three consumers.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "watergen/ir/core/diagnostic.h"
#include "watergen/ir/core/source_location.h"
#include "watergen/runtime/host_values.h"

namespace watergen {

enum class Type : uint8_t {
    Error, // result of an ill-typed operation; propagates without further diagnostics
    Bool,
    Int,
    Float,
    Vec2,
    Vec3,
    Vec4,
    Mat3,
    Texture2D,
    TextureCube,
    Tuple, // the carried values of a loop or the results of a switch, read one by one
};

// Components of a value of this type (Mat3 = 9, column-major); 0 for handles and Error.
int component_count(Type t);
// Float for 1, Vec2..Vec4 for 2..4.
Type float_type(int components);
bool is_float_numeric(Type t); // Float, Vec2, Vec3, Vec4
bool is_vector(Type t);        // Vec2, Vec3, Vec4
// GLSL spelling, used in diagnostics and reflection ("vec3").
const char* type_name(Type t);

enum class Op : uint8_t {
    // leaves
    Constant, // values = components
    Uniform,  // name = member of the parameter block
    Varying,  // name = fragment input
    Texture,  // name = texture binding
    // arithmetic (scalar operands broadcast against vectors)
    Add,
    Sub,
    Mul,
    Div,
    Neg,
    // logic (scalars)
    Less,
    LessEqual,
    Greater,
    GreaterEqual,
    Equal,
    NotEqual,
    And,
    Or,
    Not,
    Select, // args: condition (Bool), if_true, if_false
    // shape
    Swizzle,   // values = component indices
    Construct, // vector from scalars/vectors, or Mat3 from three Vec3 columns
    Splat,     // scalar -> vector of `type`
    // intrinsics
    Dot,
    Cross,
    Normalize,
    Length,
    Mix,
    Clamp,
    Saturate,
    Pow,
    Exp,
    Exp2,
    Log,
    Sqrt,
    Rsqrt,
    Abs,
    Sign,
    Min,
    Max,
    Sin,
    Cos,
    Atan2,
    Reflect,
    Refract,
    Step,
    Smoothstep,
    Fract,
    Floor,
    Mod, // GLSL semantics: x - y * floor(x / y)
    MatMulVec,
    Sample,      // args: texture, coordinate
    SampleLevel, // args: texture, coordinate, lod
    Ddx,
    Ddy,
    // bounded loops (see LoopBody)
    Loop,       // args: the carried values' initial values, [the trip count,] the captured values
    LoopResult, // args: the Loop; values[0] = carried index; the value after the last iteration
    LoopIndex,  // in a loop body: the iteration, 0, 1, ... as a float
    Carried,    // in a loop body: values[0] = carried index; its value at this iteration's start
    Captured,   // in a loop body: values[0] = capture index; an outer value the body reads
    // arrays
    UniformElement, // name = array parameter, args: index (Float; floored, clamped to the array)
    // uniform choices (see SwitchCases)
    Switch,       // args: the selector, then each case's captured outer values, case after case
    SwitchResult, // args: the Switch; values[0] = result index; the selected case's result
};
// Every op has a row in op_table.cpp (op_table.h), which checks that it has one for each op up
// to this, the last.
constexpr Op kLastOp = Op::SwitchResult;

// From the op table.
const char* op_name(Op op);
bool is_leaf(Op op);  // Constant, Uniform, Varying, Texture, LoopIndex, Carried, Captured
bool is_infix(Op op); // written between its operands: + - * / comparisons && ||

class Graph;
struct LoopBody;
struct SwitchCases;

struct Node {
    Op op = Op::Constant;
    Type type = Type::Error;
    std::vector<uint32_t> args;
    std::vector<double> values; // Constant components, Swizzle indices
    std::string name;           // leaf name, or a hint for the emitted temporary
    std::string origin;         // feature node that created it, e.g. "fresnel.schlick"
    // Relaxed precision (the precision=half axis): mediump in GLSL, min16float in HLSL, and
    // rounded to binary16 by the CPU evaluator's half mode.
    bool relaxed = false;
    // Op::Loop: what the loop does, shared by every copy of the node (immutable once built).
    std::shared_ptr<const LoopBody> loop;
    // Op::Switch: its cases, shared likewise.
    std::shared_ptr<const SwitchCases> cases;
};

// The graphs a node runs inside itself: a loop's body, a switch's cases; none for other nodes.
std::vector<const Graph*> bodies_of(const Node& n);

// Who wrote a node: the file and line where a project registered it (a node added out of tree,
// axis_registry.h), or nothing for watergen's own nodes. A parameter or texture two authors
// declare is one only when both give the same definition (a project reading watergen's
// ior_water() through its header); otherwise it is an error naming both
// (Graph::declare_parameter), so one project's node cannot silently change another's.
struct Author {
    std::string file{}; // "" for watergen's own nodes
    int line = 0;

    bool builtin() const { return file.empty(); }
    std::string label() const; // "fog.cpp:31", or "watergen" for watergen's own nodes
    friend bool operator==(const Author& a, const Author& b) {
        return a.file == b.file && a.line == b.line;
    }
};

// A uniform parameter a feature node reads. Parameters are data: defaults and ranges travel
// with the node that declares them, so presets and validation need no shader knowledge.
struct Parameter {
    std::string name{}; // member name in the parameter block, e.g. "absorb_coefficients"
    Type type = Type::Float;
    std::vector<double> default_value{};
    double min = 0.0, max = 0.0; // valid range, per component
    std::string unit{};          // "1/m", "m", "" ...
    std::string seed{};          // where it comes from, e.g. "003"
    std::string origin{};        // declaring feature node
    // Baked at pipeline creation as specialization constants instead of read from the uniform
    // block (see ir/specialization.h; EmitOptions can ask the same for a whole shader).
    bool specialization = false;
    // 0: not an array. N > 0: N elements of `type` (default_value holds all of them, element
    // after element), read with element() in dsl.h; min/max bound every element.
    uint32_t array_size = 0;
    Author author = {}; // set on declaration from the graph's author (Graph::set_author)
    // The C++ that wrote this definition (its aggregate initialisation): a clash of two
    // definitions of one name names both places.
    SourceLocation defined_at = SourceLocation::current();
    // A switch: 0 or 1 only (a convention the shader reads as > 0.5); 0.5 is refused, not
    // drawn as 0.
    bool flag = false;
    // How the host makes the value the shader reads from the values set (runtime/host_values.h):
    // a world position moved into the shader's frame, or a phase or tile offset computed in
    // double from the time and the frame centre. Given: the value as set.
    HostValue host{};
};

// Numbers in a parameter's value: its type's components, times its elements for an array.
size_t value_count(const Parameter& p);
// Whether two declarations of a parameter are one definition: type, default, range, unit,
// seed, specialization and size (not who wrote them, nor where).
bool same_definition(const Parameter& a, const Parameter& b);
// "parameter 'x' is declared by a at file:line and by b at file:line with different
// definitions: ...": the error a clash of two definitions of one name reports.
std::string definition_clash(const std::string& what, const std::string& name,
                             const std::string& origin, const SourceLocation& at,
                             const std::string& other_origin, const SourceLocation& other_at);

struct TextureInput {
    std::string name;
    Type type = Type::Texture2D;
    std::string description;
    std::string origin;
    Author author = {};                                    // set on declaration, as for Parameter
    SourceLocation defined_at = SourceLocation::current(); // as for Parameter
};

struct Output {
    std::string name;
    uint32_t node = 0;
};

// A quantity a client layer states facts about (a scene's water depth, its camera position),
// named by a typed handle rather than by a node's display name: renaming a temporary or a
// parameter cannot detach a fact from the node it bounds. Handles are declared once, as
// constants, by the layer that knows the quantity; `id` and `parameter` are string literals.
struct Quantity {
    std::string_view id; // identity, e.g. "water_depth"
    Type type = Type::Float;
    std::string_view parameter; // the uniform it stands for, "" for a computed value

    friend bool operator==(const Quantity& a, const Quantity& b) { return a.id == b.id; }
    friend bool operator<(const Quantity& a, const Quantity& b) { return a.id < b.id; }
};

struct QuantityBinding {
    Quantity quantity;
    uint32_t node = 0;
};

// Owns the DAG. Identical nodes (op, type, args, payload) are created once. Ill-typed
// operations record a Diagnostic naming the current feature node and yield an Error node.
class Graph {
  public:
    uint32_t add(Node node);
    const Node& node(uint32_t id) const { return nodes_[id]; }
    size_t size() const { return nodes_.size(); }

    // Feature node that subsequent operations belong to (see OriginScope in dsl.h).
    const std::string& origin() const { return origin_; }
    void set_origin(std::string origin) { origin_ = std::move(origin); }
    // Author of subsequent declarations and diagnostics (see AuthorScope in dsl.h): an error
    // then carries the author's file and line.
    const Author& author() const { return author_; }
    void set_author(Author author) { author_ = std::move(author); }
    // Whether subsequent operations are relaxed precision (see RelaxedScope in dsl.h).
    bool relaxed() const { return relaxed_; }
    void set_relaxed(bool relaxed) { relaxed_ = relaxed; }

    void error(std::string message);
    const Diagnostics& diagnostics() const { return diagnostics_; }

    // Declares a parameter once; a second declaration must agree on type, default and
    // specialization, and another author's must be the same definition (Author). The name must
    // be an identifier that no shading language reserves (ir/identifier.h).
    void declare_parameter(const Parameter& p);
    const std::vector<Parameter>& parameters() const { return parameters_; }
    const Parameter* find_parameter(const std::string& name) const;
    // Replaces a declared parameter's default; false when it is not declared or the component
    // count differs.
    bool set_parameter_default(const std::string& name, const std::vector<double>& value);
    // Replaces a declared parameter's range (every component); false when it is not declared.
    bool set_parameter_range(const std::string& name, double min, double max);

    void declare_texture(const TextureInput& t);
    const std::vector<TextureInput>& textures() const { return textures_; }

    void set_output(std::string name, uint32_t node);
    const std::vector<Output>& outputs() const { return outputs_; }

    // Ids reachable from the outputs, ascending (ascending id is a topological order).
    std::vector<uint32_t> live_nodes() const;

    // Binds `node` to `quantity`: a side table, no part of node identity, so hash-consing
    // keeps it; the fold pass carries it to the folded graph. A node may stand for several
    // quantities and a quantity for several nodes. Checked binding: bind() in dsl.h.
    void bind(const Quantity& quantity, uint32_t node);
    const std::vector<QuantityBinding>& bindings() const { return bindings_; }

    // While this graph is a loop body being built (dsl.h, loop()): the enclosing graph, which
    // holds the parameters and textures the body declares, and the outer values the body
    // captures. capture() gives the body's node for an outer one: constants and textures are
    // copied, other values become Captured leaves, one per outer node.
    void begin_body(Graph* enclosing) {
        enclosing_ = enclosing;
        author_ = enclosing->author_;
    }
    void end_body() { enclosing_ = nullptr; }
    Graph* enclosing() const { return enclosing_; }
    uint32_t capture(uint32_t outer);
    const std::vector<uint32_t>& captures() const { return captures_; }

  private:
    struct KeyHash {
        size_t operator()(const std::string& s) const { return std::hash<std::string>{}(s); }
    };
    std::vector<Node> nodes_;
    std::unordered_map<std::string, uint32_t, KeyHash> index_;
    std::string origin_;
    Author author_;
    bool relaxed_ = false;
    Diagnostics diagnostics_;
    std::vector<Parameter> parameters_;
    std::vector<TextureInput> textures_;
    std::vector<Output> outputs_;
    std::vector<QuantityBinding> bindings_;
    Graph* enclosing_ = nullptr;
    std::vector<uint32_t> captures_; // outer node per Captured index
};

// The compiler hint a loop is written with. The IR keeps the loop whatever the hint.
enum class UnrollHint {
    Keep,   // [[dont_unroll]] / [loop]: one copy of the body, short to compile
    Unroll, // [[unroll]] / [unroll]
    // No attribute: the driver decides. For a count a specialization constant fixes: after
    // specialization the driver knows it and unrolls a short loop (lavapipe does), which
    // [[dont_unroll]] would forbid, and which [[unroll]] cannot promise before then.
    Driver,
};

// A bounded loop: at most `trip_count` iterations of `body`, a graph whose leaves are
// LoopIndex, Carried k (k < carried), Captured m (an outer value, argument first_capture() + m
// of the Loop node; parameters and inputs come in this way too), constants and textures. Its
// outputs "next0", "next1", ... are the carried values of the next iteration, typed like the
// initial values; an optional Bool output "continue" ends the loop where it is false (per pixel,
// after the carried values are updated). The enclosing graph's parameters hold the body's: a body
// never declares its own.
struct LoopBody {
    std::shared_ptr<const Graph> body;
    std::vector<Type> carried_types; // one per carried value
    std::vector<bool> carried_relaxed;
    int trip_count = 0;
    UnrollHint unroll = UnrollHint::Keep;
    bool has_exit = false;
    // A trip count from data: argument carried() of the Loop node, a Float the same for every
    // pixel and already floored; the loop runs min(it, trip_count) iterations, none when it is
    // below 1 or NaN.
    bool counted = false;
    size_t carried() const { return carried_types.size(); }
    size_t first_capture() const { return carried() + (counted ? 1 : 0); }
};

// A uniform choice between graphs: case k runs where the selector (a Float the same on every
// pixel of a draw: built from constants and parameters only) equals k; any other value (and
// NaN) runs the last case. Each case is a graph like a loop body, whose leaves are Captured m
// (argument case_args[k] + m of the Switch node), constants and textures; its outputs "out0",
// "out1", ... are the results, typed alike in every case. Only the selected case runs, so cases
// may take derivatives and sample with implicit LOD (the control flow is uniform).
struct SwitchCases {
    std::vector<std::shared_ptr<const Graph>> cases;
    std::vector<size_t> case_args; // per case: index of its first captured value among the args
    std::vector<Type> result_types;
    std::vector<bool> result_relaxed;
    size_t results() const { return result_types.size(); }
    // The case a selector value runs.
    size_t case_for(double selector) const;
};

} // namespace watergen
