// compose_switch(): an axis offered with several choices in one shader. Each choice composes its
// own copy of the surface inside a case of a switch on the axis' selector; every field comes out
// of the switch (choose() passes the untouched ones straight through).
#include "watergen/water/axis_registry.h"
#include "watergen/water/surface.h"
#include "watergen/water/water_shader.h"

namespace watergen {

namespace {

size_t field_index(Surface& s, const Expr& field) {
    const std::vector<Expr*> fields = surface_fields(s);
    for (size_t i = 0; i < fields.size(); ++i)
        if (fields[i] == &field) return i;
    return fields.size();
}

} // namespace

void compose_switch(Surface& s, const std::string& axis, const std::vector<std::string>& choices,
                    bool specialized) {
    Graph& g = s.g;
    OriginScope scope(g, "switch." + axis);
    Parameter p{.name = selector_parameter(axis),
                .type = Type::Float,
                .default_value = {0.0},
                .max = static_cast<double>(choices.size() - 1),
                .origin = "switch." + axis};
    p.specialization = specialized;
    const Expr selector = uniform(g, p);
    const std::vector<Expr*> fields = surface_fields(s);
    auto case_body = [&](Graph& body, int c) {
        Surface in(body);
        const std::vector<Expr*> inside = surface_fields(in);
        // Every value the case reads is captured here, so what it computes from them is the
        // case's own work, run only when the case is selected.
        for (size_t i = 0; i < fields.size(); ++i)
            if (fields[i]->valid()) *inside[i] = read_in(body, *fields[i]);
        compose_choice(in, axis, choices[static_cast<size_t>(c)]);
        std::vector<Expr> out;
        for (Expr* f : inside)
            out.push_back(*f);
        return out;
    };
    // Only the wave models with derivatives set wave_slope: the flat water plane's is (0, 0),
    // which is what its case gives when another case of the switch sets it.
    const size_t slope = field_index(s, s.wave_slope);
    auto fill = [slope](Graph& body, size_t result, Type) {
        return result == slope ? constant(body, {0.0, 0.0}) : Expr();
    };
    const std::vector<Expr> results =
        choose(g, selector, static_cast<int>(choices.size()), case_body, fill);
    if (results.size() != fields.size()) return; // the error is recorded
    for (size_t i = 0; i < fields.size(); ++i)
        *fields[i] = results[i];
}

} // namespace watergen
