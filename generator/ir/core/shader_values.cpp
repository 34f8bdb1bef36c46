// Host rules over a graph's parameters (shader_values.h).
#include "watergen/ir/core/shader_values.h"

#include <cmath>
#include <stdexcept>

namespace watergen {

namespace {

// The scene quantity eye_position's parameter (water/mesh_shader.cpp): the frame follows it.
constexpr const char* kEyeParameter = "eye_position";

const std::vector<double>* given_value(const std::vector<Parameter>& parameters,
                                       const ParameterValues& given, const std::string& name) {
    const Parameter* p = nullptr;
    for (const Parameter& q : parameters)
        if (q.name == name) p = &q;
    if (auto it = given.find(name); it != given.end())
        if (!p || it->second.size() == p->default_value.size()) return &it->second;
    return p ? &p->default_value : nullptr;
}

} // namespace

FrameCentre frame_centre_for(const std::vector<Parameter>& parameters,
                             const ParameterValues& given) {
    const std::vector<double>* eye = given_value(parameters, given, kEyeParameter);
    if (!eye || eye->size() != 3) return {};
    return frame_centre_of((*eye)[0], (*eye)[2]);
}

bool is_frame_eye(const Parameter& p) {
    return p.name == kEyeParameter && p.host.rule == HostRule::FramePoint;
}

std::vector<std::pair<double, double>> host_value_range(const Parameter& p) {
    const size_t n = static_cast<size_t>(component_count(p.type));
    std::vector<std::pair<double, double>> out(n, {p.min, p.max});
    const std::pair<double, double> moved{p.min - kFrameReach, p.max + kFrameReach};
    constexpr double kPi = 3.14159265358979323846;
    switch (p.host.rule) {
    case HostRule::Given:
        break;
    case HostRule::FramePoint:
    case HostRule::FramePointXZ: {
        const size_t z = p.host.rule == HostRule::FramePoint ? 2 : 1;
        if (n <= z) break;
        const std::pair<double, double> r =
            is_frame_eye(p) ? std::pair{-kFrameCell / 2, kFrameCell / 2} : moved;
        out[0] = out[z] = r;
        break;
    }
    case HostRule::FrameWorldToClip:
    case HostRule::FrameClipToWorld:
        // A column plus the others times the centre: bounded by the declared ranges.
        for (auto& r : out)
            r = {-(std::abs(p.min) + std::abs(p.max)) * (1.0 + 2.0 * kFrameReach),
                 (std::abs(p.min) + std::abs(p.max)) * (1.0 + 2.0 * kFrameReach)};
        break;
    case HostRule::WavePhases:
        out.assign(n, {-kPi, kPi});
        break;
    case HostRule::ScrollOffset:
    case HostRule::TileOffset:
        out.assign(n, {0.0, 1.0});
        break;
    }
    return out;
}

void add_host_inputs(const std::vector<Parameter>& parameters, std::set<std::string>& read) {
    for (const Parameter& p : parameters)
        if (read.count(p.name)) read.insert(p.host.inputs.begin(), p.host.inputs.end());
}

bool has_host_values(const std::vector<Parameter>& parameters) {
    for (const Parameter& p : parameters)
        if (p.host.rule != HostRule::Given) return true;
    return false;
}

ParameterValues host_values(const std::vector<Parameter>& parameters, const ParameterValues& given,
                            const std::optional<FrameCentre>& centre) {
    ParameterValues out;
    if (!has_host_values(parameters)) return out;
    const FrameCentre c = centre ? *centre : frame_centre_for(parameters, given);
    const GivenValues read = [&](const std::string& name) {
        return given_value(parameters, given, name);
    };
    for (const Parameter& p : parameters) {
        if (p.host.rule == HostRule::Given) continue;
        const std::vector<double>* own = host_rule_computed(p.host.rule)
                                             ? &p.default_value
                                             : given_value(parameters, given, p.name);
        std::string error;
        auto v = host_value(p.host, *own, read, Frame{c, {}}, &error);
        if (!v) throw std::invalid_argument("parameter '" + p.name + "': " + error);
        out[p.name] = std::move(*v);
    }
    return out;
}

} // namespace watergen
