// Binding map files: the JSON layer and read_binding_map. Every input either yields a map or at
// least one error diagnostic; a map it yields has no clash, every index within its bounds, and
// reads back from its own file (binding_map_json) as the same slots.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "watergen/plan/binding_map_file.h"

namespace {

bool same_slots(const watergen::BindingMap& a, const watergen::BindingMap& b) {
    if (a.slots.size() != b.slots.size() || a.push_constant_bytes != b.push_constant_bytes)
        return false;
    for (size_t i = 0; i < a.slots.size(); ++i) {
        const auto &x = a.slots[i], &y = b.slots[i];
        if (x.name != y.name || x.kind != y.kind || x.set != y.set || x.binding != y.binding ||
            x.hlsl_register != y.hlsl_register || x.hlsl_space != y.hlsl_space ||
            x.msl_index != y.msl_index || x.gl_unit != y.gl_unit)
            return false;
    }
    return true;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace watergen;
    Diagnostic error;
    const auto source = JsonSource::parse(std::string(reinterpret_cast<const char*>(data), size),
                                          "fuzz.json", &error);
    if (!source) return 0;
    Diagnostics ds;
    const auto map = read_binding_map(*source, ds);
    if (!map) {
        if (!has_errors(ds)) std::abort(); // a refusal must say why
        return 0;
    }
    if (map->conflict()) std::abort();
    for (const ResourceSlot& s : map->slots)
        if (s.set > kMaxSet || s.binding > kMaxBindingIndex || s.hlsl_register > kMaxBindingIndex ||
            s.hlsl_space > kMaxBindingIndex || s.msl_index > kMaxBindingIndex ||
            s.gl_unit > kMaxBindingIndex)
            std::abort();
    // Its own file, read again: the same slots (the order of a base's, then the file's).
    const auto again_source =
        JsonSource::parse(binding_map_json(*map).dump(2), "again.json", &error);
    if (!again_source) std::abort();
    Diagnostics again_ds;
    const auto again = read_binding_map(*again_source, again_ds);
    if (!again || !same_slots(*map, *again)) std::abort();
    return 0;
}
