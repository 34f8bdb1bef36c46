// The shader's frame (runtime/host_values.h): the water pass and the mesh stages work in
// positions relative to the frame centre c, within half a metre of the eye, and read what depends
// on world positions and the time through values the host computes in double. These are those
// values' parameters, and the test that tells a scene's clock from a catalog node's time.
#pragma once

#include <string>

#include "watergen/ir/core/dsl.h"
#include "watergen/ir/core/ir.h"

namespace watergen {

// Whether `time` is the scene's clock, the `time` parameter (scene_time, mesh_shader.h): the
// positions beside it are then in the frame, and a phase or scroll reads its offset from the
// host. Any other time (a catalog node's input) comes with world positions, and the node
// computes from both as given.
bool is_scene_clock(Expr time);

// Wave i's phase offset f_i (d_i . c) + s_i t, reduced into [-pi, pi) (HostRule::WavePhases):
// "<family>_wave_phases", one element per wave of the family's arrays.
Parameter wave_phase_offsets(const std::string& family, uint32_t waves);

// The offset a scrolling tile adds to (frame position) * scale: c scale + rate t reduced into
// [0, 1) (HostRule::ScrollOffset), two components per component of `scale`. Declares the time
// it reads.
Expr scroll_offset(Graph& g, const std::string& name, const Parameter& scale,
                   const Parameter& rate);

// The offset a fixed tile of `size` metres adds to (frame position) / size: c / size reduced
// into [0, 1) (HostRule::TileOffset). 0 in a graph without an eye (its positions are world).
Parameter tile_offset(const std::string& name, const std::string& size);

} // namespace watergen
