// Values the host computes in double before a shader reads them in float: the conditioning that
// keeps waves, scrolls and positions exact at any time and any distance from the world origin
// (docs/user-guide.md, "Time and distance"). Part of watergen_reflection (standard library
// only): the generator's packer, its CPU evaluator, the runtime's UniformWriter and the
// generated C++ header compute the same numbers with these functions.
//
// The shader works in a frame whose origin is the frame centre c, a point of the water plane
// (y = 0) within half a metre of the eye per axis (frame_centre_of). Positions the engine sets in
// world coordinates (the eye, a map's window, a matrix to or from clip space) are moved into the
// frame on the host; a phase or texture coordinate the shader would compute from a world position
// and the time, f (d . x) + s t, is split into f (d . (x - c)), small in float, and an offset
// f (d . c) + s t, computed here in double-double arithmetic and reduced by its period (2 pi, or
// 1 for a tile) before it is rounded to float. The float phase that reaches sin and cos then
// stays within [-pi, pi) plus f times the distance from the frame centre, at every time and
// every distance from the world origin.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace watergen {

enum class HostRule : uint8_t {
    Given,            // the value as set
    FramePoint,       // a world point (x, y, z): x and z less the frame centre's
    FramePointXZ,     // components 0 and 1 are a world (x, z), less the frame centre's
    FrameWorldToClip, // column 3 of a world-to-clip matrix, whose columns 0 and 2 are the inputs
    FrameClipToWorld, // a column of a clip-to-world matrix; its input, a flag, says the matrix
                      // gives camera-relative positions already (then the column is as given)
    // Computed (never set): from the inputs alone.
    WavePhases,   // inputs time, frequency, frequency gain, speeds[n], directions[n]: per wave
                  // phi_i = reduce(f_i (d_i . c) + s_i t, 2 pi), f_i = f gain^i
    ScrollOffset, // inputs time, scale[n], rate[2n]: per k the pair reduce(c scale_k +
                  // (rate_2k, rate_2k+1) t, 1)
    TileOffset,   // input size: reduce(c / size, 1)
};

struct HostValue {
    HostRule rule = HostRule::Given;
    std::vector<std::string> inputs{}; // the parameters the rule reads, in its order
    friend bool operator==(const HostValue&, const HostValue&) = default;
};

// "given", "frame_point", ... (the manifest's spelling); nullopt for an unknown name.
const char* host_rule_name(HostRule rule);
std::optional<HostRule> host_rule_from_name(std::string_view name);
// Whether the rule's value is computed from its inputs only: an engine never sets it.
bool host_rule_computed(HostRule rule);
// Inputs the rule reads.
size_t host_rule_inputs(HostRule rule);

// The frame centre is the centre of the whole-metre cell the eye's (x, z) is in: the eye stays
// within half a metre of it per axis, so the shader's positions are camera-relative to 3e-8 m
// in float: a difference of two points near the eye (a view vector, a reflected ray) keeps as
// many digits as at the world origin. The centre moves only when the eye crosses a whole metre,
// which is a snap of every clipmap level whose cells are a whole number of half metres, so a
// vertex buffer in the frame (water_grid.h) is rebuilt no more often than the clipmap snaps.
// The centre, a multiple of half a metre, keeps a dyadic grid's points exact in the frame.
// (A 64 m cell, tried first, left the eye up to 32 m from the centre and tripled the
// depth-buffer path's error there: bench stability.)
inline constexpr double kFrameCell = 1.0;

// How far the frame centre may lie from the world origin: the eye's declared range (10,000 km,
// water/mesh_shader.cpp) and a cell.
inline constexpr double kFrameReach = 1e7 + kFrameCell;

struct FrameCentre {
    double x = 0, z = 0;
    friend bool operator==(const FrameCentre&, const FrameCentre&) = default;
};
FrameCentre frame_centre_of(double eye_x, double eye_z);

// Where the frame is: its centre in the coordinates the values are given in, and the world
// position of those coordinates' zero (an engine's floating origin; 0 for world coordinates).
// The frame rules move given positions by `centre`; the computed rules take the centre's world
// position, origin + centre, which they add in double-double.
struct Frame {
    FrameCentre centre{};
    FrameCentre origin{};
};

// A value as set, by parameter name (double, world coordinates, seconds); nullptr when the
// parameter has none.
using GivenValues = std::function<const std::vector<double>*(const std::string& name)>;

// The value the shader reads for a parameter with rule `h`, whose own value as set is `own`
// (the frame rules transform it; a computed rule sizes its result by it). nullopt and `error`
// (naming the input) when an input is missing or has the wrong size.
std::optional<std::vector<double>> host_value(const HostValue& h, const std::vector<double>& own,
                                              const GivenValues& given, const Frame& frame,
                                              std::string* error);

// phi = f (d . p) + s t for p = frame.origin + frame.centre, reduced into [-pi, pi), to about
// 1e-16 rad relative to the unreduced phase's magnitude (double-double products and sums, and
// Cody-Waite with a three-part 2 pi).
double wave_phase_offset(double frequency, double dx, double dz, double speed, double time,
                         const Frame& frame);
// (origin + x) scale + rate t reduced into [0, 1), likewise.
double scroll_offset(double origin, double x, double scale, double rate, double time);

} // namespace watergen
