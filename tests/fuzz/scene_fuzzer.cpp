// Scene files, then planning the scene against the built-in default material (fixed values,
// ranges and reflection sources reach the planner). Every refusal carries an error diagnostic.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "watergen/plan/scene_file.h"
#include "watergen/plan/scene_pruning.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace watergen;
    static const Material material = default_material();
    Diagnostic error;
    const auto source = JsonSource::parse(std::string(reinterpret_cast<const char*>(data), size),
                                          "fuzz.json", &error);
    if (!source) return 0;
    Diagnostics ds;
    const auto scene = parse_scene(*source, ds);
    if (!scene) {
        if (!has_errors(ds)) std::abort();
        return 0;
    }
    const auto plan = plan_scene(material, *scene, ds);
    if (!plan && !has_errors(ds)) std::abort();
    return 0;
}
