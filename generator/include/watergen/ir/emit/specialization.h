// Parameters baked at pipeline creation as Vulkan specialization constants instead of read from
// the uniform block: an engine that knows a value when it builds the pipeline lets the driver
// fold it into the shader. A float parameter is one constant; a vector parameter is one float
// constant per component (name_x, name_y, ...), composed into the vector in the source.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "watergen/ir/core/ir.h"
#include "watergen/runtime/reflection.h"

namespace watergen {

// One specialization constant: a float parameter, or one component of a vector parameter.
struct SpecializationSlot {
    uint32_t id = 0;            // constant_id (SpecId)
    std::string name;           // declared name: the parameter's, or "<parameter>_x" ... "_w"
    std::string parameter;      // the parameter it belongs to
    uint32_t component = 0;     // 0 for a float parameter
    double default_value = 0.0; // the parameter's default component
    double min = 0.0, max = 0.0;
};

// Whether `p` is emitted as specialization constants: its own flag or its name in `names`.
bool is_specialized(const Parameter& p, const std::set<std::string>& names);

// The slots of the specialized parameters of `parameters`, ids 0, 1, ... in declaration order
// and component order. A parameter that is not a float scalar or vector is an error.
std::vector<SpecializationSlot> specialization_slots(const std::vector<Parameter>& parameters,
                                                     Diagnostics& diagnostics);

// An error for each name in `names` that no parameter of `parameters` declares (a misspelt
// option would otherwise silently keep the parameter in the uniform block).
void check_specialization_names(const std::vector<Parameter>& parameters,
                                const std::set<std::string>& names, Diagnostics& diagnostics);

// The value of every slot (double -> float): the component of `overrides` for its parameter
// when present (and of the right size), else the default; what pack_uniforms is to the block.
std::map<uint32_t, float>
specialization_values(const std::vector<SpecializationSlot>& slots,
                      const std::map<std::string, std::vector<double>>& overrides = {});

// Fills the range of each reflected specialization constant from the slot of the same id and
// name (SPIR-V holds id, type and default, not the parameter's range).
void add_specialization_ranges(Reflection& reflection,
                               const std::vector<SpecializationSlot>& slots);

} // namespace watergen
