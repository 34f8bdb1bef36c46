// A stage's reflection JSON as the runtime reads it (reflection_from_json): whatever the bytes,
// a Reflection or an error, never both; a Reflection it returns survives the round trip through
// reflection_to_json unchanged (the generator writes the same form it reads).
#include <cstdint>
#include <cstdlib>
#include <string>

#include "watergen/runtime/reflection.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace watergen;
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::string error;
    const auto r = reflection_from_json(text, &error);
    if (!r) {
        if (error.empty()) std::abort();
        return 0;
    }
    if (!error.empty()) std::abort();
    const std::string once = reflection_to_json(*r);
    // A name that is not UTF-8 is written with U+FFFD in its place (3 bytes for each byte):
    // it may then pass the 4 KiB string limit; the round trip is checked for the others.
    if (once.find("\xEF\xBF\xBD") != std::string::npos) return 0;
    const auto again = reflection_from_json(once, &error);
    if (!again || reflection_to_json(*again) != once) std::abort();
    return 0;
}
