// The frame's host values (frame.h).
#include "watergen/water/frame.h"

#include "watergen/water/mesh_shader.h"

namespace watergen {

namespace {

constexpr double kPi = 3.14159265358979323846;

} // namespace

bool is_scene_clock(Expr time) {
    if (!time.valid()) return false;
    const Graph* g = &time.graph();
    const Node* n = &g->node(time.id());
    // Inside a switch case being built (an axis offered with several choices) the clock is a
    // capture of the enclosing graph's: the case is framed exactly as its own variant is.
    while (n->op == Op::Captured && g->enclosing()) {
        const uint32_t outer = g->captures().at(static_cast<size_t>(n->values.at(0)));
        g = g->enclosing();
        n = &g->node(outer);
    }
    return n->op == Op::Uniform && n->name == "time";
}

Parameter wave_phase_offsets(const std::string& family, uint32_t waves) {
    Parameter p{.name = family + "_wave_phases",
                .type = Type::Float,
                .default_value = std::vector<double>(waves, 0.0),
                .min = -kPi,
                .max = kPi,
                .unit = "rad",
                .seed = "004"};
    p.array_size = waves;
    p.host = {HostRule::WavePhases,
              {"time", family + "_frequency", family + "_frequency_gain", family + "_wave_speeds",
               family + "_wave_directions"}};
    return p;
}

Expr scroll_offset(Graph& g, const std::string& name, const Parameter& scale,
                   const Parameter& rate) {
    // The host reads the clock. A switch case's clock is its enclosing graph's, declared there
    // (is_scene_clock); binding it again inside the case would bind the quantity to a capture.
    if (!g.enclosing()) scene_time(g);
    const int pairs = component_count(scale.type);
    Parameter p{.name = name,
                .type = float_type(2 * pairs),
                .default_value = std::vector<double>(size_t(2 * pairs), 0.0),
                .max = 1.0,
                .seed = scale.seed};
    p.host = {HostRule::ScrollOffset, {"time", scale.name, rate.name}};
    return uniform(g, p);
}

Parameter tile_offset(const std::string& name, const std::string& size) {
    Parameter p{.name = name, .type = Type::Vec2, .default_value = {0.0, 0.0}, .max = 1.0};
    p.host = {HostRule::TileOffset, {size}};
    return p;
}

} // namespace watergen
