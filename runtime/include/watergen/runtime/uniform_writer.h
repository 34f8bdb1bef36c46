// Uniform block writer: an engine sets a variant's parameters by name, with type checks, and
// packs them into the bytes of its uniform buffer exactly where one language's reflection puts
// each member. Part of watergen::runtime.
//
// Layouts: pack() takes the fragment reflection of the language the engine draws with. The
// GLSL path's reflection gives the std140 layout, the HLSL path's the HLSL cbuffer layout
// (packoffset rules); the writer never recomputes offsets by a rule of its own: every member is
// written at its reflected offset, array elements at the reflected stride, and the reflected
// size is checked against the member's type. Members the compiler dropped (the manifest
// declares them, the reflection does not) are not written. The buffer is the reflected block
// size rounded up to 16 bytes (both layouts size a block in 16-byte registers); padding is zero.
//
// Push constants: when the build's binding map makes the block a push constant, the reflection
// has it as Reflection::push_constant, laid out as the uniform block would be (the generator
// keeps the std140 / cbuffer offsets); pack() writes it the same way. Push the first
// push_constant()->block_size bytes rounded up to 4 (VariantPipeline::push_constant()), not the
// 16-byte rounded whole, which may be past the range.
//
// Values start at the manifest's defaults (the material's values). In the branching build mode
// the variant's selector members are preset and cannot be set (they choose the variant).
//
// Parameters the scene folded away (manifest folded_parameters / removed_parameters), chosen
// behaviour:
//  - folded to a constant: setting the folded value again is a no-op that succeeds and says so
//    (Write::note); any other value is an error naming the parameter, the folded value and the
//    scene, because the shader can no longer show it.
//  - removed without a value (its term is gone from this variant): any value is a no-op that
//    succeeds and says so in Write::note.
// Unknown names and wrong types are errors naming both the parameter and the types.
//
// Time and distance (host_values.h): values are kept in double as set, and pack() makes what
// the shader reads from them. Set the time (seconds, up to a year) and every position in world
// coordinates, in double, or relative to a floating origin the engine names with
// set_floating_origin(); the writer moves the eye, the windows and the matrices into the frame
// around the eye and computes the wave phases and tile offsets in double. A computed member
// (a phase offset) cannot be set. A companion pass (caustics) is packed in its grid's frame:
// set_frame({PassGrid::centre, the floating origin}).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "watergen/runtime/reflection.h"
#include "watergen/runtime/shader_build.h"

namespace watergen {

struct Write {
    bool ok = false;
    std::string note;  // set on a no-op: why the value has no effect
    std::string error; // set when !ok
};

class UniformWriter {
  public:
    // Keeps a reference to `variant` (and so to its ShaderBuild): they must outlive the writer.
    explicit UniformWriter(const BuildVariant& variant);

    // float / vec2 / vec3 / vec4 by the number of values, or every element of an array
    // parameter (array_size * components values, element by element).
    Write set(const std::string& name, std::span<const float> values);
    Write set(const std::string& name, float value) { return set(name, std::span(&value, 1)); }
    Write set(const std::string& name, std::initializer_list<float> values) {
        return set(name, std::span(values.begin(), values.size()));
    }
    // The same in double: what the host rules compute from (time, world positions).
    Write set(const std::string& name, std::span<const double> values);
    Write set_time(double seconds) { return set("time", std::span(&seconds, 1)); }
    // Positions set are relative to the world point (x, z) (an engine's floating origin); the
    // waves and tiles stay where they are in the world as the origin moves. Default (0, 0).
    void set_floating_origin(double x, double z) { origin_ = {x, z}; }
    // The frame pack() uses: given by set_frame, else around the eye_position set (in the
    // floating origin's coordinates).
    Frame frame() const;
    void set_frame(const Frame& frame) { frame_ = frame; }

    bool has(const std::string& name) const { return values_.count(name) != 0; }
    // Whether pack() computes the member from others (a host rule's): set() refuses it.
    bool computed(const std::string& name) const;
    // The value as set (rounded to float), not what pack() writes for a host rule.
    std::optional<std::vector<float>> value(const std::string& name) const;

    // The block's bytes laid out as `reflection` (a stage's reflection of one language path)
    // says, its uniform buffer or else its push-constant block of the variant's block name;
    // std::nullopt and `error` when the reflection has no such block, or a member that
    // the variant does not declare or whose reflected size does not fit its type.
    std::optional<std::vector<uint8_t>> pack(const Reflection& reflection,
                                             std::string* error) const;

  private:
    struct Slot {
        const BlockParameter* parameter;
        std::vector<double> values;
    };
    const BuildVariant& variant_;
    std::map<std::string, Slot> values_;
    // Inputs of host rules that are not block members (a specialization constant a rule
    // reads, e.g. scene_camera_relative), as set.
    std::map<std::string, std::vector<double>> host_inputs_;
    FrameCentre origin_{};
    std::optional<Frame> frame_;
};

// Components of a GLSL scalar / vector type name ("vec3" -> 3); 0 for anything else.
uint32_t type_components(const std::string& type);

} // namespace watergen
