// The values a shader reads, from the values set: each parameter's host rule
// (Parameter::host, runtime/host_values.h) applied in double. What the packer writes as floats
// (pack_uniforms), what the CPU evaluator reads, and what the runtime's UniformWriter computes.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "watergen/ir/core/ir.h"

namespace watergen {

using ParameterValues = std::map<std::string, std::vector<double>>;

// The frame centre of a block whose values are `given` (else the parameters' defaults): the
// eye's (eye_position) centred in its frame cell, or the world origin for a block without
// an eye (a catalog node, a companion pass, whose caller passes the water pass' centre).
FrameCentre frame_centre_for(const std::vector<Parameter>& parameters,
                             const ParameterValues& given);

// The value of every parameter whose host rule is not Given, as the shader reads it: the
// others read their value as set. A value set for a computed parameter (a phase offset) is
// ignored: it is always computed. Throws std::invalid_argument naming the parameter when a
// rule's input is missing or malformed (a graph that declares a rule without its inputs).
ParameterValues host_values(const std::vector<Parameter>& parameters, const ParameterValues& given,
                            const std::optional<FrameCentre>& centre = std::nullopt);

// The range of each component of the value the shader reads for `p`, from p's declared range
// (that of the value as set): a frame point's x and z are within kFrameReach of it (the eye's
// within half a lattice cell of 0), a phase offset within [-pi, pi], a tile offset within [0, 1].
std::vector<std::pair<double, double>> host_value_range(const Parameter& p);

// The eye's parameter, whose position the frame follows (frame_centre_for).
bool is_frame_eye(const Parameter& p);

// Adds to `read` (parameter names a shader reads) the inputs of the host rules of those it
// reads: the block carries them, though the shader does not read them, for the host to compute
// from (`time`, a wave family's speeds).
void add_host_inputs(const std::vector<Parameter>& parameters, std::set<std::string>& read);

// Whether any parameter has a host rule: a block without one packs its values as set.
bool has_host_values(const std::vector<Parameter>& parameters);

} // namespace watergen
