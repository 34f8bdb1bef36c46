// What dsl.cpp and dsl_operators.cpp share. Private to ir/.
#pragma once

#include "watergen/ir/core/dsl.h"

namespace watergen {

// A node of type Error: what a builder returns after recording a type error on the graph, so
// that composition goes on and reports every error at once.
Expr error_expr(Graph& g);

// `e` as a value of `g`: itself, or (when `e` belongs to code enclosing the loop body `g`)
// captured into `g`, through every body in between.
Expr bring_into(Expr e, Graph& g);

} // namespace watergen
