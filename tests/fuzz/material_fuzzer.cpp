// Material files: JSON layer + MaterialBuilder. Every input either yields a material or at
// least one error diagnostic; nothing may crash, hang or grow without bound.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "watergen/plan/material.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace watergen;
    Diagnostic error;
    const auto source = JsonSource::parse(std::string(reinterpret_cast<const char*>(data), size),
                                          "fuzz.json", &error);
    if (!source) return 0;
    Diagnostics ds;
    const auto material = parse_material(*source, ds);
    if (!material && !has_errors(ds)) std::abort(); // a refusal must say why
    return 0;
}
