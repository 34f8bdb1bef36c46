#include "fragment_writer.h"

#include "watergen/ir/core/identifier.h"

#include <algorithm>
#include <fmt/format.h>

namespace watergen {

std::string strip_outer(const std::string& s) {
    if (s.size() < 2 || s.front() != '(' || s.back() != ')') return s;
    int depth = 0;
    for (size_t i = 0; i < s.size(); ++i) {
        depth += s[i] == '(' ? 1 : s[i] == ')' ? -1 : 0;
        if (depth == 0 && i + 1 < s.size()) return s;
    }
    return s.substr(1, s.size() - 2);
}

FragmentWriter::FragmentWriter(const Graph& g, const GlslSyntax& syntax, bool compute,
                               bool strict_half)
    : g_(g), syntax_(syntax), compute_(compute), strict_half_(strict_half) {
    // HLSL reads cbuffer members and textures as globals: a temporary of the same name would
    // hide them.
    for (const auto& p : g.parameters())
        own_taken_.insert(p.name);
    for (const auto& t : g.textures())
        own_taken_.insert(t.name);
}

FragmentWriter::FragmentWriter(const Graph& g, const FragmentWriter& enclosing,
                               const BodyNames& names)
    : g_(g), syntax_(enclosing.syntax_), compute_(enclosing.compute_),
      strict_half_(enclosing.strict_half_), unroll_(enclosing.unroll_),
      constants_(enclosing.constants_), array_sizes_(enclosing.array_sizes_),
      taken_(enclosing.taken_), names_(&names) {}

void FragmentWriter::read_as_constants(const ShaderInterface& in) {
    for (const auto& p : in.parameters) {
        taken_->insert(p.name);
        if (p.specialization) constants_.insert(p.name);
        if (p.array_size) array_sizes_[p.name] = p.array_size;
    }
}

namespace {

// Whether a value is spelled in a binary16 type: strict half, relaxed, and a float.
bool spelled_half(Type t, bool relaxed, bool strict_half) {
    return strict_half && relaxed && (is_float_numeric(t) || t == Type::Mat3);
}

} // namespace

bool FragmentWriter::is_half(uint32_t id) const {
    return spelled_half(g_.node(id).type, g_.node(id).relaxed, strict_half_);
}

namespace {

// Whether `pred` holds for a live node of `g` or of a loop body or switch case in it.
template <class P> bool any_live(const Graph& g, const P& pred) {
    for (uint32_t id : g.live_nodes()) {
        if (pred(g, id)) return true;
        for (const Graph* body : bodies_of(g.node(id)))
            if (any_live(*body, pred)) return true;
    }
    return false;
}

} // namespace

bool FragmentWriter::writes_half() const {
    const bool strict = strict_half_;
    return any_live(g_, [strict](const Graph& g, uint32_t id) {
        return spelled_half(g.node(id).type, g.node(id).relaxed, strict);
    });
}

bool FragmentWriter::writes_loop() const {
    return any_live(g_, [](const Graph& g, uint32_t id) { return g.node(id).op == Op::Loop; });
}

std::vector<Line> FragmentWriter::body(std::vector<std::string>& results, std::set<Op>& used_ops) {
    std::vector<Line> out = lines(used_ops);
    for (const auto& o : g_.outputs())
        results.push_back(strip_outer(expr_as(o.node, false)));
    return out;
}

std::vector<Line> FragmentWriter::lines(std::set<Op>& used_ops) {
    const std::vector<uint32_t> live = g_.live_nodes();
    std::vector<int> uses(g_.size(), 0);
    for (uint32_t id : live)
        for (uint32_t a : g_.node(id).args)
            ++uses[a];
    for (const auto& o : g_.outputs())
        ++uses[o.node];

    // A node gets a named temporary when it is shared, carries a name, or its user belongs to
    // another feature node: every line then belongs to exactly one feature node. A loop is a
    // block of lines named like a temporary; its results are its carried variables.
    std::vector<uint32_t> single_user(g_.size(), UINT32_MAX);
    for (uint32_t id : live)
        for (uint32_t a : g_.node(id).args)
            single_user[a] = id;
    for (uint32_t id : live) {
        const Node& n = g_.node(id);
        used_ops.insert(n.op);
        if (is_leaf(n.op) || n.op == Op::LoopResult || n.op == Op::SwitchResult ||
            n.type == Type::Texture2D || n.type == Type::TextureCube)
            continue;
        const bool cross_origin =
            single_user[id] != UINT32_MAX && g_.node(single_user[id]).origin != n.origin;
        // An array element's name is its array's (identity, not a naming hint).
        const bool has_name = !n.name.empty() && n.op != Op::UniformElement;
        if (uses[id] > 1 || has_name || cross_origin || n.op == Op::Loop || n.op == Op::Switch ||
            must_be_named(id, single_user[id]))
            temp_[id] = unique_name(n, id);
    }

    std::vector<Line> out;
    std::string current_origin = "\x01";
    for (uint32_t id : live) {
        auto it = temp_.find(id);
        if (it == temp_.end()) continue;
        const Node& n = g_.node(id);
        if (n.origin != current_origin) {
            if (!out.empty()) out.push_back({"", ""});
            out.push_back({syntax_.comment(n.origin.empty() ? "(unnamed)" : n.origin), n.origin});
            current_origin = n.origin;
        }
        if (n.op == Op::Loop) {
            loop_lines(id, out, used_ops);
            continue;
        }
        if (n.op == Op::Switch) {
            switch_lines(id, out, used_ops);
            continue;
        }
        out.push_back({declared_type(n.type, n.relaxed, is_half(id)) + " " + it->second + " = " +
                           strip_outer(spell(id)) + ";",
                       n.origin});
    }
    return out;
}

std::string FragmentWriter::declared_type(Type t, bool relaxed, bool half) const {
    if (!strict_half_) return syntax_.temp_type(t, relaxed);
    return half ? syntax_.half_type(t) : syntax_.type(t);
}

namespace {

// The order in which a loop's carried variables take their next values, and which of them go
// through a temporary first. A next value written inline reads some carried variables
// (`reads[k]`, itself aside): it is assigned before any of those changes. Where such reads form
// a cycle, the smallest index in it takes a temporary (computed before any assignment).
std::vector<size_t> assignment_order(const std::vector<std::set<size_t>>& reads,
                                     std::vector<bool>& via_temp) {
    const size_t count = reads.size();
    std::vector<bool> done(count, false);
    std::vector<size_t> order;
    // Whether j can change now: no variable still to be assigned inline reads it.
    auto ready = [&](size_t j) {
        for (size_t k = 0; k < count; ++k)
            if (!done[k] && k != j && !via_temp[k] && reads[k].count(j)) return false;
        return true;
    };
    while (order.size() < count) {
        size_t next = count;
        for (size_t j = 0; j < count && next == count; ++j)
            if (!done[j] && ready(j)) next = j;
        if (next == count) { // a cycle: break it at its smallest index
            for (size_t j = 0; j < count; ++j)
                if (!done[j] && !via_temp[j]) {
                    via_temp[j] = true;
                    break;
                }
            continue;
        }
        done[next] = true;
        order.push_back(next);
    }
    return order;
}

} // namespace

// The carried variables node `id` of a loop body reads where it is written inline (up to the
// body's temporaries, which hold their values already).
void FragmentWriter::inline_carried(uint32_t id, std::set<size_t>& out) const {
    if (temp_.count(id)) return;
    const Node& n = g_.node(id);
    if (n.op == Op::Carried) out.insert(static_cast<size_t>(n.values[0]));
    for (uint32_t a : n.args)
        inline_carried(a, out);
}

// T loop_c0 = init0; ...
// [[dont_unroll]] for (int loop_i = 0; loop_i < N; ++loop_i) {
//     if (!(float(loop_i) < trip_count)) break;   (a trip count from data)
//     <body>
//     T loop_n1 = next1;   (only where next values read each other's carried variables in a cycle)
//     bool loop_go = keep_going;
//     loop_c0 = next0; loop_c1 = loop_n1; ...   (each before the variables its next value reads
//                                                change; none where the value stays)
//     if (!loop_go) break;
// }
void FragmentWriter::loop_lines(uint32_t id, std::vector<Line>& out, std::set<Op>& used_ops) {
    const Node& n = g_.node(id);
    const LoopBody& body = *n.loop;
    const std::string& base = temp_.at(id);
    BodyNames names;
    names.index = base + "_i";
    std::vector<bool> half(body.carried());
    std::vector<std::string> types(body.carried());
    for (size_t k = 0; k < body.carried(); ++k) {
        const Type t = body.carried_types[k];
        names.carried.push_back(base + "_c" + std::to_string(k));
        half[k] = spelled_half(t, body.carried_relaxed[k], strict_half_);
        types[k] = declared_type(t, body.carried_relaxed[k], half[k]);
        out.push_back({types[k] + " " + names.carried[k] + " = " +
                           strip_outer(expr_as(n.args[k], half[k])) + ";",
                       n.origin});
    }
    for (size_t m = body.first_capture(); m < n.args.size(); ++m)
        names.captured.push_back(strip_outer(expr(n.args[m])));
    const UnrollHint unroll = emitted_hint(unroll_, body.unroll);
    out.push_back({syntax_.loop_header(names.index, body.trip_count, unroll), n.origin});
    std::vector<Line> inside;
    // A NaN count compares false: no iteration, as the CPU evaluator runs it.
    if (body.counted)
        inside.push_back({"if (!(" + syntax_.int_to_float(names.index) + " < " +
                              strip_outer(expr_as(n.args[body.carried()], false)) + ")) break;",
                          n.origin});
    FragmentWriter inner(*body.body, *this, names);
    for (Line& l : inner.lines(used_ops))
        inside.push_back(std::move(l));
    uint32_t keep_going = UINT32_MAX;
    std::vector<uint32_t> next;
    for (const auto& o : body.body->outputs()) {
        if (o.name == "continue")
            keep_going = o.node;
        else
            next.push_back(o.node); // "next0", "next1", ... in order
    }
    std::vector<std::set<size_t>> reads(body.carried());
    for (size_t k = 0; k < body.carried(); ++k) {
        inner.inline_carried(next[k], reads[k]);
        reads[k].erase(k);
    }
    std::vector<bool> via_temp(body.carried(), false);
    const std::vector<size_t> order = assignment_order(reads, via_temp);
    std::vector<std::string> value(body.carried());
    for (size_t k = 0; k < body.carried(); ++k) {
        value[k] = strip_outer(inner.expr_as(next[k], half[k]));
        if (!via_temp[k]) continue;
        inside.push_back(
            {types[k] + " " + base + "_n" + std::to_string(k) + " = " + value[k] + ";", n.origin});
        value[k] = base + "_n" + std::to_string(k);
    }
    if (keep_going != UINT32_MAX)
        inside.push_back({syntax_.type(Type::Bool) + " " + base +
                              "_go = " + strip_outer(inner.expr(keep_going)) + ";",
                          n.origin});
    for (size_t k : order)
        if (value[k] != names.carried[k])
            inside.push_back({names.carried[k] + " = " + value[k] + ";", n.origin});
    if (keep_going != UINT32_MAX) inside.push_back({"if (!" + base + "_go) break;", n.origin});
    for (auto& l : inside)
        out.push_back({l.text.empty() ? "" : "    " + l.text, l.origin});
    out.push_back({"}", n.origin});
}

// T choice_r0; ...            (every result declared before the cases)
// if (selector == 0.0) {
//     <case 0>
//     choice_r0 = out0; ...
// } else if (selector == 1.0) {
//     ...
// } else {
//     <last case>
// }
void FragmentWriter::switch_lines(uint32_t id, std::vector<Line>& out, std::set<Op>& used_ops) {
    const Node& n = g_.node(id);
    const SwitchCases& cases = *n.cases;
    const std::string& base = temp_.at(id);
    std::vector<bool> half(cases.results());
    for (size_t k = 0; k < cases.results(); ++k) {
        const Type t = cases.result_types[k];
        half[k] = spelled_half(t, cases.result_relaxed[k], strict_half_);
        out.push_back({declared_type(t, cases.result_relaxed[k], half[k]) + " " + base + "_r" +
                           std::to_string(k) + ";",
                       n.origin});
    }
    const std::string selector = strip_outer(expr(n.args[0]));
    for (size_t c = 0; c < cases.cases.size(); ++c) {
        const bool last = c + 1 == cases.cases.size();
        const std::string test =
            "if (" + selector + " == " + syntax_.literal(static_cast<double>(c)) + ") {";
        // One case runs whatever the selector says: a plain block.
        const std::string head = c == 0 ? (last ? "{" : test)
                                 : last ? "} else {"
                                        : "} else " + test;
        out.push_back({head, n.origin});
        BodyNames names;
        const size_t first = cases.case_args[c];
        const size_t end = last ? n.args.size() : cases.case_args[c + 1];
        for (size_t m = first; m < end; ++m)
            names.captured.push_back(strip_outer(expr(n.args[m])));
        const Graph& body = *cases.cases[c];
        FragmentWriter inner(body, *this, names);
        std::vector<Line> inside = inner.lines(used_ops);
        for (size_t k = 0; k < cases.results(); ++k)
            inside.push_back({base + "_r" + std::to_string(k) + " = " +
                                  strip_outer(inner.expr_as(body.outputs()[k].node, half[k])) + ";",
                              n.origin});
        for (auto& l : inside)
            out.push_back({l.text.empty() ? "" : "    " + l.text, l.origin});
    }
    out.push_back({"}", n.origin});
}

std::string FragmentWriter::unique_name(const Node& n, uint32_t id) {
    std::string base = !n.name.empty()      ? safe_identifier(n.name)
                       : n.op == Op::Loop   ? fmt::format("loop{}", id)
                       : n.op == Op::Switch ? fmt::format("choice{}", id)
                                            : fmt::format("t{}", id);
    std::string name = base;
    for (int k = 2; taken_->count(name); ++k)
        name = fmt::format("{}_{}", base, k);
    taken_->insert(name);
    return name;
}

// glslang turns ?: into branches unless both operands are plain names, and a branch inside
// a texture() argument leaves OpSampledImage in another block than its use (spirv-val
// rejects it). Selects, their operands and sample coordinates are therefore temporaries:
// every select becomes OpSelect and every sample sees a finished coordinate.
// In a compute stage a quad difference synchronises the workgroup, so it must run in main's
// straight-line code, never inside a short-circuit operand.
bool FragmentWriter::must_be_named(uint32_t id, uint32_t user) const {
    const Op own = g_.node(id).op;
    if (own == Op::Select || (compute_ && (own == Op::Ddx || own == Op::Ddy))) return true;
    if (user == UINT32_MAX) return false;
    const Op op = g_.node(user).op;
    // A loop's initial and captured values, and a switch's, are read in its body by name.
    return op == Op::Select || op == Op::Sample || op == Op::SampleLevel || op == Op::Loop ||
           op == Op::Switch;
}

std::string FragmentWriter::expr(uint32_t id) {
    if (auto it = temp_.find(id); it != temp_.end()) return it->second;
    return spell(id);
}

// Node `id` at 16 bits (`half`) or 32: converted where its own width differs.
std::string FragmentWriter::expr_as(uint32_t id, bool half) {
    const Type t = g_.node(id).type;
    if (is_half(id) == half || !(is_float_numeric(t) || t == Type::Mat3)) return expr(id);
    return syntax_.convert(t, half, strip_outer(expr(id)));
}

// The node's own operation with its arguments spelled (inline or by temporary name). In a
// strict-half shader the arguments take the node's width, except the coordinates and level
// of a texture sample: sampling is 32-bit and its result is converted.
std::string FragmentWriter::spell(uint32_t id) {
    const Node& n = g_.node(id);
    const bool half = is_half(id);
    const bool sample = n.op == Op::Sample || n.op == Op::SampleLevel;
    if (half && sample) {
        const bool compute_sample = compute_ && n.op == Op::Sample;
        return syntax_.convert(n.type, true, strip_outer(spell_at(id, false, compute_sample)));
    }
    return spell_at(id, half || compares_halves(n), compute_ && n.op == Op::Sample);
}

// A comparison of two binary16 values compares them at 16 bits: widening is exact, so the
// result is the 32-bit comparison's, without the two conversions.
bool FragmentWriter::compares_halves(const Node& n) const {
    const bool comparison = n.op == Op::Less || n.op == Op::LessEqual || n.op == Op::Greater ||
                            n.op == Op::GreaterEqual || n.op == Op::Equal || n.op == Op::NotEqual;
    return comparison && !n.args.empty() &&
           std::all_of(n.args.begin(), n.args.end(), [this](uint32_t a) { return is_half(a); });
}

// `half`: the width of the arguments and the result. `level0`: a compute stage's sample,
// which reads level 0 explicitly.
std::string FragmentWriter::spell_at(uint32_t id, bool half, bool level0) {
    const Node& n = g_.node(id);
    std::vector<std::string> a;
    std::vector<Type> types;
    for (uint32_t arg : n.args) {
        a.push_back(expr_as(arg, half));
        types.push_back(g_.node(arg).type);
    }
    switch (n.op) {
    case Op::Constant:
        return half ? syntax_.convert(n.type, true, syntax_.constant(n)) : syntax_.constant(n);
    case Op::Uniform:
        return constants_.count(n.name) ? n.name : syntax_.uniform_ref(n.name);
    case Op::UniformElement: {
        // Clamped as the CPU evaluator clamps: truncation and floor agree from 0 up.
        const auto it = array_sizes_.find(n.name);
        const uint32_t last = it != array_sizes_.end() ? it->second - 1 : 0;
        return fmt::format("{}[clamp({}, 0, {})]", syntax_.uniform_ref(n.name),
                           syntax_.float_to_int(strip_outer(a[0])), last);
    }
    case Op::Varying:
    case Op::Texture:
        return n.name;
    case Op::LoopResult:
        return temp_.at(n.args[0]) + "_c" + std::to_string(static_cast<int>(n.values[0]));
    case Op::SwitchResult:
        return temp_.at(n.args[0]) + "_r" + std::to_string(static_cast<int>(n.values[0]));
    case Op::LoopIndex:
        return syntax_.int_to_float(names_->index);
    case Op::Carried:
        return names_->carried.at(static_cast<size_t>(n.values[0]));
    case Op::Captured:
        return names_->captured.at(static_cast<size_t>(n.values[0]));
    case Op::Neg:
        return "(-" + a[0] + ")";
    case Op::Not:
        return "(!" + a[0] + ")";
    case Op::Select:
        return "(" + a[0] + " ? " + a[1] + " : " + a[2] + ")";
    case Op::Swizzle: {
        std::string s;
        for (double v : n.values)
            s += "xyzw"[static_cast<int>(v)];
        return a[0] + "." + s;
    }
    case Op::Construct:
        return syntax_.construct(n.type, a, half);
    case Op::Splat:
        return syntax_.splat(n.type, strip_outer(a[0]), half);
    default:
        break;
    }
    if (compute_ && (n.op == Op::Ddx || n.op == Op::Ddy))
        return fmt::format("probe_quad_difference({}, probe_lane, {}u)", strip_outer(a[0]),
                           n.op == Op::Ddx ? 1 : 2);
    if (level0) {
        // One mip level and the same filter for magnification and minification: level 0 is
        // what the fragment stage's implicit LOD samples too.
        a.push_back(syntax_.literal(0.0));
        types.push_back(Type::Float);
        for (auto& s : a)
            s = strip_outer(s);
        return syntax_.call(Op::SampleLevel, n.type, a, types);
    }
    if (is_infix(n.op)) return "(" + a[0] + " " + op_name(n.op) + " " + a[1] + ")";
    for (auto& s : a)
        s = strip_outer(s);
    return syntax_.call(n.op, n.type, a, types, half);
}

} // namespace watergen
