// The frame's host values (frame.h).
#include "watergen/water/frame.h"

#include "watergen/water/mesh_shader.h"

namespace watergen {

namespace {

constexpr double kPi = 3.14159265358979323846;

} // namespace

bool is_scene_clock(Expr time) {
    if (!time.valid()) return false;
    const Node& n = time.graph().node(time.id());
    return n.op == Op::Uniform && n.name == "time";
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
    scene_time(g); // the host reads it
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
