#include "watergen/ir/core/ir.h"

#include "watergen/ir/core/identifier.h"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>

namespace watergen {

int component_count(Type t) {
    switch (t) {
    case Type::Bool:
    case Type::Int:
    case Type::Float:
        return 1;
    case Type::Vec2:
        return 2;
    case Type::Vec3:
        return 3;
    case Type::Vec4:
        return 4;
    case Type::Mat3:
        return 9;
    default:
        return 0;
    }
}

Type float_type(int components) {
    switch (components) {
    case 1:
        return Type::Float;
    case 2:
        return Type::Vec2;
    case 3:
        return Type::Vec3;
    case 4:
        return Type::Vec4;
    default:
        return Type::Error;
    }
}

bool is_float_numeric(Type t) {
    return t == Type::Float || t == Type::Vec2 || t == Type::Vec3 || t == Type::Vec4;
}

bool is_vector(Type t) {
    return t == Type::Vec2 || t == Type::Vec3 || t == Type::Vec4;
}

const char* type_name(Type t) {
    switch (t) {
    case Type::Error:
        return "<error>";
    case Type::Bool:
        return "bool";
    case Type::Int:
        return "int";
    case Type::Float:
        return "float";
    case Type::Vec2:
        return "vec2";
    case Type::Vec3:
        return "vec3";
    case Type::Vec4:
        return "vec4";
    case Type::Mat3:
        return "mat3";
    case Type::Texture2D:
        return "texture2D";
    case Type::TextureCube:
        return "textureCube";
    case Type::Tuple:
        return "<tuple>";
    }
    return "?";
}

std::vector<const Graph*> bodies_of(const Node& n) {
    std::vector<const Graph*> out;
    if (n.loop) out.push_back(n.loop->body.get());
    if (n.cases)
        for (const auto& c : n.cases->cases)
            out.push_back(c.get());
    return out;
}

size_t SwitchCases::case_for(double selector) const {
    for (size_t k = 0; k + 1 < cases.size(); ++k)
        if (selector == static_cast<double>(k)) return k;
    return cases.empty() ? 0 : cases.size() - 1;
}

size_t value_count(const Parameter& p) {
    return static_cast<size_t>(component_count(p.type)) * std::max<uint32_t>(1, p.array_size);
}

namespace {

// Identity of a node for hash-consing. The name is identity for leaves only; for other nodes
// it is a naming hint, so two equal computations with different hints are still one node.
std::string node_key(const Node& n) {
    std::string key;
    key.reserve(16 + n.args.size() * 4 + n.values.size() * 8);
    key.push_back(static_cast<char>(n.op));
    key.push_back(static_cast<char>(n.type));
    key.push_back(n.relaxed ? 'r' : 'f');
    for (uint32_t a : n.args)
        key.append(reinterpret_cast<const char*>(&a), sizeof a);
    key.push_back('|');
    for (double v : n.values)
        key.append(reinterpret_cast<const char*>(&v), sizeof v);
    if (is_leaf(n.op) || n.op == Op::UniformElement) {
        key.push_back('|');
        key += n.name;
    }
    if (n.loop) { // every loop is its own
        const auto* body = n.loop.get();
        key.push_back('@');
        key.append(reinterpret_cast<const char*>(&body), sizeof body);
    }
    if (n.cases) { // and every switch
        const auto* cases = n.cases.get();
        key.push_back('#');
        key.append(reinterpret_cast<const char*>(&cases), sizeof cases);
    }
    return key;
}

} // namespace

uint32_t Graph::add(Node node) {
    // Leaves (parameters, inputs) and array elements keep full precision; operations follow
    // the current scope.
    // A loop's or a switch's result has the precision of its value, whatever the scope.
    if ((!is_leaf(node.op) && node.op != Op::LoopResult && node.op != Op::SwitchResult &&
         node.op != Op::UniformElement) ||
        node.op == Op::Constant)
        node.relaxed = node.relaxed || relaxed_;
    if (node.type == Type::Bool || node.type == Type::Texture2D || node.type == Type::TextureCube ||
        node.type == Type::Tuple)
        node.relaxed = false;
    std::string key = node_key(node);
    if (auto it = index_.find(key); it != index_.end()) {
        Node& existing = nodes_[it->second];
        if (existing.name.empty() && !node.name.empty()) existing.name = node.name;
        return it->second;
    }
    if (node.origin.empty()) node.origin = origin_;
    const auto id = static_cast<uint32_t>(nodes_.size());
    nodes_.push_back(std::move(node));
    index_.emplace(std::move(key), id);
    return id;
}

void Graph::error(std::string message) {
    diagnostics_.push_back(
        Diagnostic{Severity::Error, author_.file, author_.line, 0, origin_, std::move(message)});
}

std::string Author::label() const {
    return builtin() ? "watergen" : file + ":" + std::to_string(line);
}

namespace {

// "fog.exponential at /src/fog.cpp:31": a declaring node and where the definition was written.
std::string declared_by(const std::string& origin, const SourceLocation& at) {
    return (origin.empty() ? std::string("a node") : origin) + " at " + at.file + ":" +
           std::to_string(at.line);
}

} // namespace

bool same_definition(const Parameter& a, const Parameter& b) {
    return a.type == b.type && a.default_value == b.default_value && a.min == b.min &&
           a.max == b.max && a.unit == b.unit && a.seed == b.seed &&
           a.specialization == b.specialization && a.array_size == b.array_size &&
           a.flag == b.flag && a.host == b.host;
}

std::string definition_clash(const std::string& what, const std::string& name,
                             const std::string& origin, const SourceLocation& at,
                             const std::string& other_origin, const SourceLocation& other_at) {
    return what + " '" + name + "' is declared by " + declared_by(origin, at) + " and by " +
           declared_by(other_origin, other_at) +
           " with different definitions: a name belongs to one definition; rename one";
}

uint32_t Graph::capture(uint32_t outer) {
    const Node& o = enclosing_->node(outer);
    // Constants and texture handles are the same in the body. Parameters and inputs are
    // captured like computed values: a pass over the enclosing graph (the scene fold) then
    // sees every read of them.
    if (o.op == Op::Constant || o.op == Op::Texture) {
        Node copy = o;
        copy.origin.clear();
        return add(std::move(copy));
    }
    size_t m = 0;
    while (m < captures_.size() && captures_[m] != outer)
        ++m;
    if (m == captures_.size()) captures_.push_back(outer);
    Node n;
    n.op = Op::Captured;
    n.type = o.type;
    n.relaxed = o.relaxed;
    n.values = {static_cast<double>(m)};
    n.name = o.name;
    return add(std::move(n));
}

void Graph::declare_parameter(const Parameter& p) {
    if (enclosing_) { // a loop body's parameters are its enclosing graph's
        Parameter copy = p;
        if (copy.origin.empty()) copy.origin = origin_;
        if (copy.author.builtin()) copy.author = author_;
        enclosing_->declare_parameter(copy);
        return;
    }
    const Author& author = p.author.builtin() ? author_ : p.author;
    if (const Parameter* existing = find_parameter(p.name)) {
        // Another author's declaration is the same parameter only when it is the same
        // definition (a project reading watergen's ior_water() through its header).
        if (!(existing->author == author) && !same_definition(*existing, p)) {
            error(definition_clash("parameter", p.name, p.origin.empty() ? origin_ : p.origin,
                                   p.defined_at, existing->origin, existing->defined_at));
            return;
        }
        if (existing->type != p.type || existing->default_value != p.default_value ||
            existing->specialization != p.specialization || existing->array_size != p.array_size ||
            !(existing->host == p.host))
            error("parameter '" + p.name +
                  "' declared twice with different type, default, specialization or array size "
                  "(first by " +
                  existing->origin + ")");
        return;
    }
    if (auto problem = identifier_problem(p.name)) {
        error("parameter name: " + *problem);
        return;
    }
    Parameter copy = p;
    if (copy.origin.empty()) copy.origin = origin_;
    copy.author = author;
    if (copy.default_value.size() != value_count(copy))
        error(fmt::format("parameter '{}': default has {} components, {}{} needs {}", p.name,
                          copy.default_value.size(), type_name(copy.type),
                          copy.array_size ? fmt::format("[{}]", copy.array_size) : "",
                          value_count(copy)));
    parameters_.push_back(std::move(copy));
}

const Parameter* Graph::find_parameter(const std::string& name) const {
    for (const auto& p : parameters_)
        if (p.name == name) return &p;
    return nullptr;
}

bool Graph::set_parameter_default(const std::string& name, const std::vector<double>& value) {
    for (auto& p : parameters_)
        if (p.name == name) {
            if (p.default_value.size() != value.size()) return false;
            p.default_value = value;
            return true;
        }
    return false;
}

bool Graph::set_parameter_range(const std::string& name, double min, double max) {
    for (auto& p : parameters_)
        if (p.name == name) {
            p.min = min;
            p.max = max;
            return true;
        }
    return false;
}

void Graph::declare_texture(const TextureInput& t) {
    if (enclosing_) {
        TextureInput copy = t;
        if (copy.origin.empty()) copy.origin = origin_;
        if (copy.author.builtin()) copy.author = author_;
        enclosing_->declare_texture(copy);
        return;
    }
    const Author& author = t.author.builtin() ? author_ : t.author;
    for (const auto& existing : textures_)
        if (existing.name == t.name) {
            if (!(existing.author == author) &&
                (existing.type != t.type || existing.description != t.description))
                error(definition_clash("texture", t.name, t.origin.empty() ? origin_ : t.origin,
                                       t.defined_at, existing.origin, existing.defined_at));
            return;
        }
    if (auto problem = identifier_problem(t.name)) {
        error("texture name: " + *problem);
        return;
    }
    TextureInput copy = t;
    if (copy.origin.empty()) copy.origin = origin_;
    copy.author = author;
    textures_.push_back(std::move(copy));
}

void Graph::set_output(std::string name, uint32_t node) {
    for (auto& o : outputs_)
        if (o.name == name) {
            o.node = node;
            return;
        }
    outputs_.push_back(Output{std::move(name), node});
}

void Graph::bind(const Quantity& quantity, uint32_t node) {
    for (const auto& b : bindings_)
        if (b.quantity == quantity && b.node == node) return;
    bindings_.push_back({quantity, node});
}

std::vector<uint32_t> Graph::live_nodes() const {
    std::vector<char> live(nodes_.size(), 0);
    std::vector<uint32_t> stack;
    for (const auto& o : outputs_)
        stack.push_back(o.node);
    while (!stack.empty()) {
        uint32_t id = stack.back();
        stack.pop_back();
        if (live[id]) continue;
        live[id] = 1;
        for (uint32_t a : nodes_[id].args)
            stack.push_back(a);
    }
    std::vector<uint32_t> ids;
    for (uint32_t i = 0; i < nodes_.size(); ++i)
        if (live[i]) ids.push_back(i);
    return ids;
}

} // namespace watergen
