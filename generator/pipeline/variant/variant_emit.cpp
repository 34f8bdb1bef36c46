#include "watergen/pipeline/variant/variant_emit.h"

#include "watergen/pipeline/output/output_writer.h"

namespace watergen {

EmittedVariant emit_variant(const Variant& variant, const Preset* preset,
                            const EmitOptions& options, const std::filesystem::path& out) {
    EmittedVariant e;
    const VariantBuild build = build_variant(variant, preset, options);
    e.diagnostics = build.diagnostics;
    e.built = build.ok();
    if (!e.built) return e;
    const auto files = variant_files(build);
    e.dir = out / variant.file_stem();
    e.files = files.size();
    if (auto error = write_directory_atomically(e.dir, files)) e.error = *error;
    return e;
}

} // namespace watergen
