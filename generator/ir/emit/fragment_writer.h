// Writes a graph's live nodes as the statements of a shader function body, one temporary per
// shared or named value, every line attributed to its feature node; loops become `for` loops,
// switches `if` / `else if` chains.
// Shared by the stage emitters (emitter.cpp, vertex_emitter.cpp). Private to ir/.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "shader_syntax.h"

namespace watergen {

struct Line {
    std::string text;
    std::string origin;
};

// Removes one pair of parentheses that encloses the whole text.
std::string strip_outer(const std::string& s);

class FragmentWriter {
  public:
    // How a loop body's or switch case's leaves are spelled (set by the enclosing graph's writer).
    struct BodyNames {
        std::string index;                 // the loop counter, an int
        std::vector<std::string> carried;  // per carried value
        std::vector<std::string> captured; // per captured outer value
    };

    // `compute`: written for a compute stage (the probe), which has neither implicit-LOD sampling
    // nor derivatives: samples read level 0, ddx / ddy become quad differences (emit_probe).
    // `strict_half`: relaxed float nodes are written in explicit 16-bit types (EmitOptions).
    FragmentWriter(const Graph& g, const GlslSyntax& syntax, bool compute = false,
                   bool strict_half = false);

    // The unroll hint of every loop (EmitOptions::unroll); loop bodies inherit it.
    void set_unroll(LoopUnroll unroll) { unroll_ = unroll; }

    // Parameters of `in` that are specialization constants: read by their own name.
    void read_as_constants(const ShaderInterface& in);

    // Whether node `id` is spelled in a binary16 type: strict half, relaxed, and a float.
    bool is_half(uint32_t id) const;
    bool compares_halves(const Node& n) const; // a comparison of two binary16 values
    // Whether any live node, in loops too, is spelled in a binary16 type / is a loop (the
    // shader needs the float16 / control-flow-attributes extension).
    bool writes_half() const;
    bool writes_loop() const;

    // Lines of the body; results[i] spells output i (at 32 bits).
    std::vector<Line> body(std::vector<std::string>& results, std::set<Op>& used_ops);

  private:
    FragmentWriter(const Graph& g, const FragmentWriter& enclosing, const BodyNames& names);
    std::vector<Line> lines(std::set<Op>& used_ops);
    void loop_lines(uint32_t id, std::vector<Line>& lines, std::set<Op>& used_ops);
    void switch_lines(uint32_t id, std::vector<Line>& lines, std::set<Op>& used_ops);
    void inline_carried(uint32_t id, std::set<size_t>& out) const;
    bool must_be_named(uint32_t id, uint32_t user) const;
    std::string unique_name(const Node& n, uint32_t id);
    std::string declared_type(Type t, bool relaxed, bool half) const;
    std::string expr(uint32_t id);
    std::string expr_as(uint32_t id, bool half);
    std::string spell(uint32_t id);
    std::string spell_at(uint32_t id, bool half, bool level0);

    const Graph& g_;
    const GlslSyntax& syntax_;
    bool compute_ = false;
    bool strict_half_ = false;
    LoopUnroll unroll_ = LoopUnroll::AsHinted;
    std::set<std::string> constants_;             // parameters that are specialization constants
    std::map<std::string, uint32_t> array_sizes_; // array parameters' elements
    std::map<uint32_t, std::string> temp_;
    std::set<std::string> own_taken_;
    std::set<std::string>* taken_ = &own_taken_; // names in use, shared with enclosing writers
    const BodyNames* names_ = nullptr;           // set when g_ is a loop body
};

} // namespace watergen
