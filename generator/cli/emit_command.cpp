// watergen emit: one variant (or the pairwise covering set) built and written, each by
// emit_variant() (pipeline/variant_emit.h).
#include <cstdio>

#include "commands.h"
#include "watergen/pipeline/variant/variant_emit.h"
#include "watergen/plan/covering_array.h"

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
        if (!resolve_variant(o->covering ? default_variant() : o->variant, o->preset, &preset,
                             common))
            return kUsage;
        const std::vector<Variant> variants =
            o->covering ? pairwise_covering_variants() : std::vector<Variant>{o->variant};
        int failed = 0;
        for (const Variant& v : variants) {
            const EmittedVariant e =
                emit_variant(v, preset, EmitOptions{o->strict_half, {}, o->unroll}, o->out);
            print_diagnostics(e.diagnostics, common);
            if (!e.built)
                std::fprintf(stderr, "watergen: error: %s failed; nothing written for it\n",
                             v.key().c_str());
            else if (!e.error.empty())
                std::fprintf(stderr, "watergen: error: %s\n", e.error.c_str());
            else
                std::printf("%s -> %s (%zu files)\n", v.key().c_str(), e.dir.string().c_str(),
                            e.files);
            failed += e.ok() ? 0 : 1;
        }
        return failed ? kFailed : kOk;
    };
}

} // namespace watergen::cli
