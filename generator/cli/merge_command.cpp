// watergen merge OUT SHARD_DIR...: the outputs of `watergen build --shard I/N` for I = 1..N
// joined into exactly what one build writes.
#include <cstdio>

#include <fmt/format.h>

#include "commands.h"
#include "watergen/pipeline/shards/sharded_build.h"

namespace watergen::cli {

Runner add_merge_command(CLI::App& app) {
    struct Options {
        std::string out;
        std::vector<std::string> shards;
        std::string cache;
        bool no_cache = false;
    };
    auto o = std::make_shared<Options>();
    app.add_option("out", o->out,
                   "output directory, replaced as a whole as `watergen build --out` replaces it")
        ->required();
    app.add_option("shards", o->shards,
                   "the output directories of `watergen build --shard I/N`, one for each I")
        ->required();
    app.add_option("--cache", o->cache,
                   "cache directory where the build record goes, so that the next `watergen "
                   "build` of the same inputs into OUT does nothing (default: build's, "
                   "$XDG_CACHE_HOME/watergen or ~/.cache/watergen)");
    app.add_flag("--no-cache", o->no_cache, "store no build record");
    return [o]() {
        const std::vector<std::filesystem::path> dirs(o->shards.begin(), o->shards.end());
        const BuildCache cache =
            o->no_cache ? BuildCache()
                        : BuildCache(o->cache.empty() ? default_cache_dir()
                                                      : std::filesystem::path(o->cache));
        const MergeResult m = merge_shards(o->out, dirs, cache);
        if (!m.error.empty()) {
            std::fprintf(stderr, "watergen: error: merge: %s; nothing written\n", m.error.c_str());
            return m.write_failed ? kFailed : kUsage;
        }
        if (!m.warning.empty()) std::fprintf(stderr, "watergen: warning: %s\n", m.warning.c_str());
        std::printf("%s\n", fmt::format("merge: {} shards, {} variants -> {} ({} files)", m.shards,
                                        m.variants, o->out, m.files)
                                .c_str());
        return kOk;
    };
}

} // namespace watergen::cli
