// Names a node gives its parameters, textures and temporaries, checked once for both shading
// languages: a name must be an identifier neither GLSL nor HLSL reserves, and must not be one of
// the names the emitted skeleton declares itself (params, out_color, v_uv, the probe's buffers).
// A node added out of tree is held to this like watergen's own, so a name cannot silently hide
// a built-in function (a local `texture` hides GLSL's texture()) or a cbuffer member (HLSL
// reads cbuffer members as globals).
#pragma once

#include <optional>
#include <string>

namespace watergen {

// Why `name` cannot be a parameter or texture name, or nothing when it can:
// "'float' is reserved by GLSL / HLSL".
std::optional<std::string> identifier_problem(const std::string& name);

// `name` made safe as a temporary: characters outside [A-Za-z0-9_] become '_', and a name
// that is empty, starts with a digit, or is reserved gets a "t_" prefix.
std::string safe_identifier(const std::string& name);

} // namespace watergen
