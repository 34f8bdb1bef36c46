// `watergen emit` of one variant as a library call: built (build_variant) and its files
// (variant_files) written into <out>/<variant>/ as one atomic step.
#pragma once

#include <filesystem>
#include <string>

#include "watergen/pipeline/variant/variant_build.h"

namespace watergen {

struct EmittedVariant {
    Diagnostics diagnostics;
    bool built = false;        // false: nothing written for it
    std::filesystem::path dir; // written
    size_t files = 0;
    std::string error; // the directory could not be written
    bool ok() const { return built && error.empty(); }
};

EmittedVariant emit_variant(const Variant& variant, const Preset* preset,
                            const EmitOptions& options, const std::filesystem::path& out);

} // namespace watergen
