// Input tables of `watergen probe`, for a scalar node (one column) and a vector one (three).
#include <cstdint>
#include <cstdlib>
#include <string>

#include "watergen/eval/probe/probe_table.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace watergen;
    const std::string text(reinterpret_cast<const char*>(data), size);
    for (const std::vector<std::string>& columns :
         {std::vector<std::string>{"c"}, {"xz.x", "xz.y", "time"}}) {
        std::string error;
        const auto values = parse_probe_csv(text, "fuzz.csv", columns, error);
        if (!values && error.empty()) std::abort();
        if (values && (values->empty() || values->size() % columns.size() != 0)) std::abort();
    }
    return 0;
}
