#include <cstdio>
#include <filesystem>

#include "commands.h"
#include "watergen/pipeline/output_writer.h"
#include "watergen/pipeline/variant_build.h"
#include "watergen/plan/covering_array.h"
#include "watergen/water/presets.h"

namespace watergen::cli {

Runner add_emit_command(CLI::App& app, const Common& common) {
    struct Options {
        Variant variant = default_variant();
        std::string preset;
        bool covering = false, strict_half = false;
        LoopUnroll unroll = LoopUnroll::AsHinted;
        std::string out = "out/emit";
    };
    auto o = std::make_shared<Options>();
    add_variant_options(app, o->variant, o->preset);
    app.add_flag(
        "--covering", o->covering,
        "emit the pairwise covering set: every pair of choices on two axes in at least one variant "
        "(axis options are ignored)");
    app.add_flag("--strict-half", o->strict_half,
                 "write a half variant's relaxed math in explicit 16-bit types (GLSL float16_t, "
                 "HLSL half) instead of mediump / min16float hints; needs shaderFloat16");
    add_unroll_option(app, o->unroll);
    app.add_option("--out", o->out,
                   "output directory; each variant goes to <out>/<variant>/ (default out/emit)");
    return [o, &common]() {
        const Preset* preset = nullptr;
        if (!resolve_variant(o->covering ? default_variant() : o->variant, o->preset, &preset))
            return kUsage;
        const std::vector<Variant> variants =
            o->covering ? pairwise_covering_variants() : std::vector<Variant>{o->variant};
        int failed = 0;
        for (const Variant& v : variants) {
            const VariantBuild build =
                build_variant(v, preset, EmitOptions{o->strict_half, {}, o->unroll});
            print_diagnostics(build.diagnostics, common);
            if (!build.ok()) {
                std::fprintf(stderr, "watergen: error: %s failed; nothing written for it\n",
                             v.key().c_str());
                ++failed;
                continue;
            }
            const auto files = variant_files(build);
            const std::filesystem::path dir = std::filesystem::path(o->out) / v.file_stem();
            if (auto e = write_directory_atomically(dir, files)) {
                std::fprintf(stderr, "watergen: error: %s\n", e->c_str());
                ++failed;
                continue;
            }
            std::printf("%s -> %s (%zu files)\n", v.key().c_str(), dir.string().c_str(),
                        files.size());
        }
        return failed ? kFailed : kOk;
    };
}

} // namespace watergen::cli
