// Compiles a graph into a flat program (block_program.h): per node, once, its kernel, where
// its arguments and result lie, and how its result is rounded.
//
// - A node whose arguments are all the same on every lane (constants, parameters and what is
//   computed from them alone) is lane-invariant: computed for one lane, read by every lane. If
//   it does not depend on a loop's iteration either it is computed once, in the prologue. So
//   are a loop's carried values that stay the same on every lane (a wave's amplitude and
//   frequency in the sum over waves), and what a body computes from them alone.
// - Shape operations that only move values (a contiguous swizzle, a splat, a loop's result, a
//   loop body's captured and carried values) read their source in place when the values need
//   no further rounding; other copies are instructions.
// - Storage: after its last reader a value's place is reused (the working set is the values
//   alive at once, not the whole graph). Lane-invariant values of the prologue keep theirs.
// - Errors (a missing input, an ill-typed node) become checks, in node order.
// - A switch's selector is built from constants and parameters (dsl_switch.cpp checks it), so
//   it is computed by the prologue: the prologue compiled so far runs once, at compile time,
//   and only the case it selects is compiled, in line. The program has no switches, and as on
//   the GPU, only that case's inputs must be supplied.
#include "block_program.h"

#include "watergen/ir/core/op_table.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include "block_evaluator.h"
#include "block_inputs.h"
#include "block_invariance.h"
#include "block_kernels.h"
#include "block_storage.h"

namespace watergen {

namespace {

// The values a node can hold: binary16 values are binary32 values are doubles. Rounding a value
// to a precision that holds it changes nothing.
enum class Cls : uint8_t { Half, Float, Double };

struct Value {
    Operand at;
    uint32_t comps = 0;
    bool uniform = true; // the same on every lane
    bool hoisted = true; // computed in the prologue
    Cls cls = Cls::Half;
};

// A loop body or switch case being compiled: where its captured and carried values lie.
struct LoopScope {
    std::vector<Value> captured, carried;
};

// Values two float evaluations hold alike: inputs (constants, parameters, array elements: the
// same binary32 values on GPU and CPU), results exact given binary32 arguments (operations that
// choose, compare or count), and + - and differences, which both round to nearest. Products (a
// GPU may fuse one into the add that follows), quotients, transcendentals, the composite
// built-ins, filtering and interpolated varyings are where two float evaluations part, so
// FloatPerturbation::relative moves those alone (a loop index 3 moved to 2.9999999 would pick
// another array element).
bool same_in_binary32(Op op) {
    return op_info(op).exact_in_binary32;
}

// A texture sample, or components of one. lavapipe converts these to binary16 rounding
// toward zero (NIR folds the conversion into the sampler), other values to nearest.
bool texture_result(const Graph& g, uint32_t id) {
    const Node& n = g.node(id);
    if (n.op == Op::Swizzle) return texture_result(g, n.args[0]);
    return n.op == Op::Sample || n.op == Op::SampleLevel;
}

// A value's components, one operand each.
std::vector<Operand> components(const Value& v) {
    std::vector<Operand> all;
    for (uint32_t c = 0; c < v.comps; ++c)
        all.push_back(v.at.component(c));
    return all;
}

// Ids reachable from one node, ascending (a topological order).
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

class Compiler {
  public:
    Compiler(const Graph& top, const EvalInputs& in, EvalPrecision p, Program& program)
        : top_(top), in_(in), p_(p), program_(program), wide_(p == EvalPrecision::Double) {}

    void compile(uint32_t root);

  private:
    struct Context {
        const Graph& g;
        std::vector<Instr>& list;
        LoopScope* scope;
        std::vector<Value> values;
        std::unordered_map<uint32_t, Value> narrowed;
        std::map<std::tuple<uint32_t, uint32_t, bool>, Value> sincos; // by argument, relaxed
        std::unordered_map<uint32_t, std::vector<Value>> parts;       // by Loop or Switch node
    };

    void compile_graph(Context& ctx, const std::vector<uint32_t>& live);
    Value compile_node(Context& ctx, uint32_t id);
    Value compile_shape(Context& ctx, uint32_t id, const std::vector<Value>& args);
    Value compile_loop(Context& ctx, uint32_t id, const std::vector<Value>& args);
    Value next_value(Context& inner, uint32_t id, const std::vector<Value>& places);
    Value compile_switch(Context& ctx, uint32_t id, const std::vector<Value>& args);
    size_t selected_case(const Node& n, const Value& selector);
    Value read_through(Context& ctx, uint32_t id, const Value& src);
    Value compile_op(Context& ctx, uint32_t id, const std::vector<Value>& args);
    Value compile_sincos(Context& ctx, uint32_t id, const Value& x);
    Value read_arg(Context& ctx, const Node& consumer, size_t i);
    Value copy(Context& ctx, uint32_t id, const std::vector<Operand>& from, Cls from_cls,
               bool uniform, bool hoisted);

    Cls target(const Node& n) const {
        if (wide_) return Cls::Double;
        return p_ == EvalPrecision::Half && n.relaxed ? Cls::Half : Cls::Float;
    }
    Rounding rounding(const Graph& g, uint32_t id) const {
        if (target(g.node(id)) != Cls::Half) return Rounding::None;
        return texture_result(g, id) ? Rounding::HalfTowardZero : Rounding::Half;
    }
    Value define(uint32_t comps, bool uniform, bool hoisted, Cls cls);
    void push(Context& ctx, Instr ins, bool hoisted, std::vector<Operand> reads);
    void fail(std::string message) { program_.checks.push_back({std::move(message)}); }

    const Graph& top_;
    const EvalInputs& in_;
    EvalPrecision p_;
    Program& program_;
    bool wide_;
    StorageTimeline storage_;
};

Value Compiler::define(uint32_t comps, bool uniform, bool hoisted, Cls cls) {
    Value v;
    v.comps = comps;
    v.uniform = uniform;
    v.hoisted = hoisted;
    v.cls = cls;
    v.at.lane_step = uniform ? 0 : 1;
    v.at.comp_step = comps <= 1 ? 0 : (uniform ? 1 : static_cast<uint32_t>(kBlock));
    const uint32_t size = std::max(comps, 1u) * (uniform ? 1 : static_cast<uint32_t>(kBlock));
    v.at.slot = storage_.add(size, hoisted);
    return v;
}

// Appends an instruction: to the prologue when lane-invariant and loop-invariant, else to the
// list being compiled, at the next position of the storage timeline.
void Compiler::push(Context& ctx, Instr ins, bool hoisted, std::vector<Operand> reads) {
    if (hoisted) {
        program_.prologue.push_back(ins);
        return;
    }
    const size_t at = storage_.step();
    storage_.write(ins.out.slot, at);
    for (const Operand& o : reads)
        storage_.read(o, at);
    ctx.list.push_back(ins);
}

// In half mode a relaxed node reads its 32-bit arguments (parameters, inputs, full-precision
// islands) converted to binary16, as the GPU converts them where 16-bit arithmetic begins; a
// texture sample keeps 32-bit coordinates.
Value Compiler::read_arg(Context& ctx, const Node& consumer, size_t i) {
    const uint32_t id = consumer.args[i];
    const Value& v = ctx.values[id];
    const Node& a = ctx.g.node(id);
    const bool narrow = p_ == EvalPrecision::Half && consumer.relaxed &&
                        consumer.op != Op::Sample && consumer.op != Op::SampleLevel && !a.relaxed &&
                        (is_float_numeric(a.type) || a.type == Type::Mat3);
    if (!narrow || v.cls == Cls::Half) return v;
    if (auto it = ctx.narrowed.find(id); it != ctx.narrowed.end()) return it->second;
    Value out = define(v.comps, v.uniform, v.hoisted, Cls::Half);
    Instr ins;
    ins.kernel = narrow_kernel(texture_result(ctx.g, id));
    ins.out = out.at;
    ins.args[0] = v.at;
    ins.comps = v.comps;
    ins.per_lane = !v.uniform;
    push(ctx, ins, v.hoisted, {v.at});
    ctx.narrowed.emplace(id, out);
    return out;
}

// Node id's value as a copy of `from` (one operand per component), rounded as the node is.
Value Compiler::copy(Context& ctx, uint32_t id, const std::vector<Operand>& from, Cls from_cls,
                     bool uniform, bool hoisted) {
    const Node& n = ctx.g.node(id);
    Value out = define(static_cast<uint32_t>(from.size()), uniform, hoisted, target(n));
    Instr ins;
    ins.kernel = copy_kernel(wide_);
    ins.out = out.at;
    ins.comps = out.comps;
    ins.per_lane = !uniform;
    ins.round = from_cls <= target(n) ? Rounding::None : rounding(ctx.g, id);
    ins.aux = static_cast<uint32_t>(program_.gathers.size());
    program_.gathers.insert(program_.gathers.end(), from.begin(), from.end());
    push(ctx, ins, hoisted, from);
    return out;
}

void Compiler::compile_graph(Context& ctx, const std::vector<uint32_t>& live) {
    for (uint32_t id : live)
        ctx.values[id] = compile_node(ctx, id);
}

Value Compiler::compile_node(Context& ctx, uint32_t id) {
    const Node& n = ctx.g.node(id);
    switch (n.op) {
    case Op::Texture:
        return {};
    case Op::Captured:
        return read_through(ctx, id, ctx.scope->captured[static_cast<size_t>(n.values[0])]);
    case Op::Carried:
        return read_through(ctx, id, ctx.scope->carried[static_cast<size_t>(n.values[0])]);
    case Op::LoopResult:
    case Op::SwitchResult: // carried value or result k
        return read_through(ctx, id, ctx.parts.at(n.args[0])[static_cast<size_t>(n.values[0])]);
    default:
        break;
    }
    std::vector<Value> args;
    for (size_t i = 0; i < n.args.size(); ++i)
        args.push_back(read_arg(ctx, n, i));
    switch (n.op) {
    case Op::Swizzle:
    case Op::Splat:
    case Op::Construct:
        return compile_shape(ctx, id, args);
    case Op::Loop:
        return compile_loop(ctx, id, args);
    case Op::Switch:
        return compile_switch(ctx, id, args);
    case Op::Sin:
    case Op::Cos:
        if (!wide_ && args[0].comps == 1) return compile_sincos(ctx, id, args[0]);
        return compile_op(ctx, id, args);
    default:
        return compile_op(ctx, id, args);
    }
}

// Node id's value is `src` (a captured, carried or switch result value): read in place when it
// needs no rounding, else a rounded copy.
Value Compiler::read_through(Context& ctx, uint32_t id, const Value& src) {
    if (src.cls <= target(ctx.g.node(id))) return src;
    return copy(ctx, id, components(src), src.cls, src.uniform, src.hoisted);
}

// Operations that only move components: read in place where possible, else copied.
Value Compiler::compile_shape(Context& ctx, uint32_t id, const std::vector<Value>& args) {
    const Node& n = ctx.g.node(id);
    const auto comps = static_cast<uint32_t>(component_count(n.type));
    std::vector<Operand> from;
    Cls cls = Cls::Half;
    bool uniform = true, hoisted = true;
    for (const Value& a : args) {
        cls = std::max(cls, a.cls);
        uniform = uniform && a.uniform;
        hoisted = hoisted && a.hoisted;
    }
    if (n.op == Op::Construct) {
        for (const Value& v : args)
            for (const Operand& o : components(v))
                from.push_back(o);
        return copy(ctx, id, from, cls, uniform, hoisted);
    }
    // Component source[c] of argument 0 becomes component c.
    std::vector<uint32_t> source(comps, 0);
    bool in_place = cls <= target(n);
    for (uint32_t c = 0; c < comps; ++c) {
        if (n.op == Op::Swizzle) source[c] = static_cast<uint32_t>(n.values[c]);
        // In place: one component, a splat, or components in order without gaps (.yz).
        in_place = in_place && (n.op == Op::Splat || source[c] == source[0] + c);
        from.push_back(args[0].at.component(source[c]));
    }
    if (!in_place) return copy(ctx, id, from, cls, uniform, hoisted);
    Value v = args[0];
    v.comps = comps;
    if (comps == 1 || n.op == Op::Splat)
        v.at = from[0]; // one component for all
    else
        v.at.offset = from[0].offset;
    return v;
}

// An operation with a kernel of its own.
Value Compiler::compile_op(Context& ctx, uint32_t id, const std::vector<Value>& args) {
    const Node& n = ctx.g.node(id);
    const auto comps = static_cast<uint32_t>(component_count(n.type));
    // Derivatives stay per lane: a quad's difference of the same value is 0, or NaN for an
    // infinite one, and 0 past the end of a block.
    bool uniform = n.op != Op::Varying && n.op != Op::Ddx && n.op != Op::Ddy;
    bool hoisted = uniform && n.op != Op::LoopIndex;
    for (const Value& a : args) {
        uniform = uniform && a.uniform;
        hoisted = hoisted && a.hoisted;
    }
    hoisted = hoisted && uniform;
    Value out = define(comps, uniform, hoisted, target(n));
    Instr ins;
    ins.out = out.at;
    ins.comps = comps;
    ins.per_lane = !uniform;
    ins.round = rounding(ctx.g, id);
    ins.data = input_data(top_, ctx.g, n, comps, in_, program_.host, program_.checks);
    std::vector<Operand> reads;
    for (size_t i = 0; i < args.size() && i < 3; ++i) {
        ins.args[i] = args[i].at;
        reads.push_back(args[i].at);
    }
    const uint32_t la = args.size() > 0 ? args[0].at.lane_step : 0;
    const uint32_t lb = args.size() > 1 ? args[1].at.lane_step : 0;
    ins.kernel = op_kernel(n.op, wide_, p_ == EvalPrecision::Half && n.relaxed, la, lb);
    if (!ins.kernel) {
        fail(std::string("operation '") + op_name(n.op) + "' has no CPU evaluation");
        return out;
    }
    if (n.op == Op::Dot || n.op == Op::Length || n.op == Op::Normalize) ins.aux = args[0].comps;
    if (n.op == Op::Reflect || n.op == Op::Refract) ins.aux = args[1].comps;
    if (n.op == Op::UniformElement && ins.data) ins.aux = top_.find_parameter(n.name)->array_size;
    if (n.op == Op::Sample || n.op == Op::SampleLevel)
        ins.aux = ctx.g.node(n.args[0]).type == Type::TextureCube;
    // Every value, constants and parameters too: the GPU holds them in binary32.
    if (wide_) {
        ins.site = static_cast<uint32_t>(program_.sites.size());
        ins.exact = same_in_binary32(n.op);
        std::string operands;
        for (uint32_t a : n.args) {
            const Node& arg = ctx.g.node(a);
            operands += (operands.empty() ? "" : ", ") +
                        (arg.name.empty() ? std::string(op_name(arg.op)) : arg.name);
        }
        program_.sites.push_back({n.origin, n.name, n.op, std::move(operands)});
    }
    push(ctx, ins, hoisted, reads);
    return out;
}

// Float storage: sin(x) and cos(x) of the same x (the waves' phases) in one instruction, whose
// rows the Sin and the Cos node read.
Value Compiler::compile_sincos(Context& ctx, uint32_t id, const Value& x) {
    const Node& n = ctx.g.node(id);
    const auto key = std::tuple{x.at.slot, x.at.offset, n.relaxed};
    auto it = ctx.sincos.find(key);
    if (it == ctx.sincos.end()) {
        const Value both = define(2, x.uniform, x.hoisted, target(n));
        Instr ins;
        ins.kernel = sincos_kernel(x.at.lane_step);
        ins.out = both.at;
        ins.args[0] = x.at;
        ins.comps = 2;
        ins.per_lane = !x.uniform;
        ins.round = rounding(ctx.g, id);
        push(ctx, ins, x.hoisted, {x.at});
        it = ctx.sincos.emplace(key, both).first;
    }
    Value v = it->second;
    v.comps = 1;
    v.at = v.at.component(n.op == Op::Sin ? 0 : 1);
    return v;
}

// A loop: each carried value in a place of its own (one lane's worth when it is lane-invariant,
// block_invariance.h), the body compiled into a list of its own that reads its captured and
// carried values where they lie; LoopResult reads the places after the last iteration.
Value Compiler::compile_loop(Context& ctx, uint32_t id, const std::vector<Value>& args) {
    const Node& n = ctx.g.node(id);
    const LoopBody& body = *n.loop;
    const Graph& bg = *body.body;
    std::vector<uint32_t> next; // the body's node of each carried value's next value
    for (const auto& o : bg.outputs())
        if (o.name != "continue") next.push_back(o.node);
    std::vector<char> invariant_args;
    for (const Value& a : args)
        invariant_args.push_back(a.uniform);
    const std::vector<char> invariant = invariant_carried(n, invariant_args);
    LoopPlan plan;
    plan.trip_count = body.trip_count;
    plan.has_exit = body.has_exit;
    const size_t start = storage_.step();
    LoopScope scope;
    for (size_t k = 0; k < body.carried(); ++k) {
        // What the place holds: the initial value, then the body's next values.
        const auto comps = static_cast<uint32_t>(component_count(body.carried_types[k]));
        const Value place =
            define(comps, invariant[k], false, std::max(args[k].cls, target(bg.node(next[k]))));
        storage_.write(place.at.slot, start);
        storage_.read(args[k].at, start);
        plan.carried.push_back({place.at, args[k].at, {}, comps});
        scope.carried.push_back(place);
    }
    if (body.counted) {
        plan.counted = true;
        plan.count = args[body.carried()].at;
        storage_.read(plan.count, start);
    }
    scope.captured.assign(args.begin() + static_cast<std::ptrdiff_t>(body.first_capture()),
                          args.end());
    if (plan.trip_count > 0) {
        storage_.open_loop();
        Context inner{bg, plan.body, &scope, std::vector<Value>(bg.size()), {}, {}, {}};
        compile_graph(inner, bg.live_nodes());
        for (size_t k = 0; k < next.size(); ++k) {
            const Value v = next_value(inner, next[k], scope.carried);
            // block_invariance.h's promise, checked: a slip would give wrong values silently.
            if (invariant[k] && !v.uniform) fail("loop: a lane-invariant carried value varies");
            plan.carried[k].next = v.at;
        }
        for (const auto& o : bg.outputs())
            if (o.name == "continue") plan.keep_going = inner.values[o.node].at;
    }
    const size_t end = storage_.step();
    if (plan.trip_count > 0) storage_.close_loop(start, end);
    for (const auto& c : plan.carried) {
        storage_.read(c.storage, end);
        storage_.read(c.next, end);
    }
    storage_.read(plan.keep_going, end);
    Instr ins;
    ins.kernel = loop_kernel(wide_);
    ins.per_lane = true;
    ins.aux = static_cast<uint32_t>(program_.loops.size());
    program_.loops.push_back(std::move(plan));
    ctx.list.push_back(ins);
    std::vector<Value>& results = ctx.parts[id]; // rounded as the Loop node is
    for (const Value& place : scope.carried)
        results.push_back(read_through(ctx, id, place));
    return {};
}

// The next value of a carried value: body node `id`'s value, or a copy of it if it lies in one
// of the loop's places (passed on as it is, it would be overwritten while the others are still
// read from it).
Value Compiler::next_value(Context& inner, uint32_t id, const std::vector<Value>& places) {
    const Value& v = inner.values[id];
    for (const Value& place : places)
        if (v.at.slot == place.at.slot)
            return copy(inner, id, components(v), v.cls, v.uniform, false);
    return v;
}

// The case a switch runs. Its selector is computed by the prologue compiled so far, which runs
// here as every evaluator will run it. Once an input is missing the evaluation fails at an
// earlier check whatever the case (and the prologue may not run): the last case.
size_t Compiler::selected_case(const Node& n, const Value& selector) {
    const SwitchCases& cases = *n.cases;
    if (!selector.hoisted) {
        fail("switch: the selector is not the same on every lane");
        return cases.cases.size() - 1;
    }
    for (const Check& c : program_.checks)
        if (c.varying_size == SIZE_MAX) return cases.cases.size() - 1;
    Program now;
    now.wide = wide_;
    now.prologue = program_.prologue;
    now.gathers = program_.gathers;
    now.root = selector.at;
    now.root_comps = 1;
    storage_.place(now);
    double value = 0;
    BlockEvaluator(now, in_).read_root(1, &value);
    return cases.case_for(value);
}

// A switch: its selected case compiled in line, reading the Switch node's arguments as its
// captured values; its results, rounded as the Switch node is, are what SwitchResult reads.
Value Compiler::compile_switch(Context& ctx, uint32_t id, const std::vector<Value>& args) {
    const Node& n = ctx.g.node(id);
    const SwitchCases& cases = *n.cases;
    const size_t c = selected_case(n, args[0]);
    const Graph& cg = *cases.cases[c];
    const size_t end = c + 1 < cases.cases.size() ? cases.case_args[c + 1] : args.size();
    LoopScope scope;
    scope.captured.assign(args.begin() + static_cast<std::ptrdiff_t>(cases.case_args[c]),
                          args.begin() + static_cast<std::ptrdiff_t>(end));
    Context inner{cg, ctx.list, &scope, std::vector<Value>(cg.size()), {}, {}, {}};
    compile_graph(inner, cg.live_nodes());
    std::vector<Value>& results = ctx.parts[id];
    for (const auto& o : cg.outputs())
        results.push_back(read_through(ctx, id, inner.values[o.node]));
    return {};
}

void Compiler::compile(uint32_t root) {
    Context ctx{top_, program_.main, nullptr, std::vector<Value>(top_.size()), {}, {}, {}};
    compile_graph(ctx, live_from(top_, root));
    const Value& v = ctx.values[root];
    program_.root = v.at;
    program_.root_comps = v.comps;
    storage_.read(v.at, storage_.step());
    storage_.place(program_);
}

} // namespace

Program compile_program(const Graph& g, uint32_t root, const EvalInputs& in, EvalPrecision p) {
    Program program;
    program.wide = p == EvalPrecision::Double;
    try {
        program.host = host_values(g.parameters(), in.uniforms, in.frame_centre);
    } catch (const std::invalid_argument& e) {
        program.checks.push_back({e.what()});
    }
    Compiler(g, in, p, program).compile(root);
    return program;
}

std::string block_error(const Program& program, size_t begin, size_t count) {
    for (const Check& c : program.checks)
        if (c.varying_size == SIZE_MAX || c.varying_size < (begin + count) * c.varying_comps)
            return c.message;
    return {};
}

} // namespace watergen
