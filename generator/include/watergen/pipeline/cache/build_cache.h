// Content-addressed cache of built variants: the key is an xxHash64 over everything a
// variant's files depend on (emitted sources, parameter metadata, key, preset) plus the
// versions of watergen and of the toolchain libraries, so an unchanged variant is copied
// instead of compiled, and any change of input or tool misses. Nothing in the cache is trusted:
// an entry is used only when it is a regular file holding exactly the expected files, each
// with its size and XXH3-128 hash; anything else is evicted and rebuilt.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "watergen/ir/core/diagnostic.h"

namespace watergen {

using FileMap = std::map<std::string, std::string>; // relative path -> contents

// "watergen 0.1.0; glslang 12.0.0; SPIRV-Tools ...; SPIRV-Cross C API 0.54.0"
const std::string& toolchain_fingerprint();

// xxHash64 over the fingerprint and `parts` (each length-prefixed, so part boundaries count),
// as 16 lower-case hex digits.
std::string content_hash(const std::vector<std::string>& parts);

// XXH3-128 of one file's bytes, as 32 lower-case hex digits: what an entry records per file.
std::string file_digest(std::string_view bytes);
// The text of an XXH3-128 value as file_digest() writes it (for digests taken piece by piece).
std::string digest_text(uint64_t high, uint64_t low);
// One file as an entry stores it: "<path>\n<size>\n<file_digest>\n<bytes>".
std::string cache_record(const std::string& path, const std::string& bytes);

// Entries larger than this are damage, not variants (a variant's files are a few hundred KB).
constexpr size_t kMaxCacheEntryBytes = size_t(64) << 20;

struct CacheLookup {
    std::optional<FileMap> files; // on a hit: exactly the expected files, verified
    std::string
        rejected; // non-empty: an entry was there, failed verification (why) and was evicted
};

// What BuildCache::load_or_make() gave.
struct CacheUse {
    std::optional<FileMap> files; // nullopt: not in the cache and make() failed
    bool cached = false;          // copied from the cache
    std::string rejected;         // as CacheLookup::rejected
};

class BuildCache {
  public:
    BuildCache() = default; // disabled
    explicit BuildCache(std::filesystem::path dir)
        : dir_(std::move(dir)), unwritable_(std::make_shared<std::once_flag>()) {}
    bool enabled() const { return !dir_.empty(); }
    const std::filesystem::path& dir() const { return dir_; }

    // The files stored under `hash` if the entry holds exactly `expected` (relative paths),
    // each of the recorded size and hash; otherwise a miss, and a damaged entry is evicted.
    CacheLookup load(const std::string& hash, const std::vector<std::string>& expected) const;
    // Stores atomically (temporary + rename, safe across threads and processes); an error
    // message on failure, which callers may ignore (the build does not depend on the cache).
    std::optional<std::string> store(const std::string& hash, const FileMap& files) const;

    // The files under `hash` (load()), or else make()'s, stored under `hash` when it made
    // them (nullopt: it failed, and nothing is stored). A store that fails (a full disk, a
    // read-only directory, a cache path under a regular file) leaves no temporary file and is
    // reported once per cache, on stderr: "watergen: warning: cache <dir> cannot be written
    // (<why>); building without storing".
    CacheUse load_or_make(const std::string& hash, const std::vector<std::string>& expected,
                          const std::function<std::optional<FileMap>()>& make) const;

    // The file that holds the entry for `hash`.
    std::filesystem::path entry(const std::string& hash) const;
    // The build's warning for the entry of `hash` that failed verification (`why`).
    Diagnostic rejected_warning(const std::string& hash, const std::string& why) const;

  private:
    void warn_unwritable(const std::string& why) const;
    std::filesystem::path dir_;
    std::shared_ptr<std::once_flag> unwritable_; // shared by copies: one warning per cache
};

// ${XDG_CACHE_HOME:-$HOME/.cache}/watergen, or "" when neither variable is set.
std::filesystem::path default_cache_dir();

} // namespace watergen
