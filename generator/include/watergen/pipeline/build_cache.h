// Content-addressed cache of built variants: the key is an xxHash64 over everything a
// variant's files depend on (emitted sources, parameter metadata, key, preset) plus the
// versions of watergen and of the toolchain libraries, so an unchanged variant is copied
// instead of compiled, and any change of input or tool misses.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace watergen {

using FileMap = std::map<std::string, std::string>; // relative path -> contents

// "watergen 0.1.0; glslang 12.0.0; SPIRV-Tools ...; SPIRV-Cross C API 0.54.0"
const std::string& toolchain_fingerprint();

// xxHash64 over the fingerprint and `parts` (each length-prefixed, so part boundaries count),
// as 16 lower-case hex digits.
std::string content_hash(const std::vector<std::string>& parts);

class BuildCache {
public:
    BuildCache() = default; // disabled
    explicit BuildCache(std::filesystem::path dir) : dir_(std::move(dir)) {}
    bool enabled() const { return !dir_.empty(); }
    const std::filesystem::path& dir() const { return dir_; }

    // The files stored under `hash`; nullopt on a miss or an unreadable entry.
    std::optional<FileMap> load(const std::string& hash) const;
    // Stores atomically (temporary + rename, safe across threads and processes); an error
    // message on failure, which callers may ignore (the build does not depend on the cache).
    std::optional<std::string> store(const std::string& hash, const FileMap& files) const;

private:
    std::filesystem::path entry(const std::string& hash) const;
    std::filesystem::path dir_;
};

// ${XDG_CACHE_HOME:-$HOME/.cache}/watergen, or "" when neither variable is set.
std::filesystem::path default_cache_dir();

} // namespace watergen
