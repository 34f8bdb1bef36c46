// watergen_shaders.h: the C++ header of a build, beside its manifest.json, for an engine that
// skips the runtime library. Made from the finished output (the manifest and each shader's
// variant.json), so an unsharded build and the merge of its shards write the same bytes.
//
// It holds, in namespace watergen_<material>:
// - bindings::<resource>: every resource's place in the build's binding map (Vulkan set and
//   binding, HLSL register and space, Metal index, GL unit);
// - one struct per distinct uniform block of the build (WaterParams0, WaterParams1, ...), laid
//   out as std140 and the HLSL cbuffer both read it (uniform_layout.h): float members, explicit
//   padding, each parameter's default as its initialiser, static_asserts of every offset and of
//   the size; an interface's specialization-constant ids beside its struct;
// - kVariants: every variant's scene, key, short hash and interface (which struct), and
//   with_interface(i, f), which calls f with interface i's default block.
#pragma once

#include <functional>
#include <optional>
#include <string>

namespace watergen {

constexpr const char* kShadersHeader = "watergen_shaders.h";

// A file of the output, by its path relative to the output directory; nullopt if absent.
using ReadOutputFile = std::function<std::optional<std::string>(const std::string& path)>;

// The header's text, or nullopt with *error (a file missing or malformed).
std::optional<std::string> shaders_header(const ReadOutputFile& read, std::string* error);

class StagedTree;
// Writes the header of what `tree` holds (its manifest.json written) into it: the build's last
// step and the merge's. The error names the header.
std::optional<std::string> write_shaders_header(StagedTree& tree);

} // namespace watergen
