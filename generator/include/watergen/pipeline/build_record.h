// What an output directory was made from, so that a rebuild with nothing changed does nothing.
// After a build publishes its output, it stores a record in the cache directory (one per output
// path): a key over the material and scene files' bytes, the build options, the shard, the
// toolchain versions and the watergen executable itself, and every file it wrote with its size
// and XXH3-128 hash. The next build with the same key whose output still holds exactly those
// bytes (every file re-read and re-hashed; sizes first) leaves the output untouched and does no
// IR work at all. Anything else (no record, another key, a file changed, missing or unreadable)
// is a normal build.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "watergen/pipeline/build_cache.h"

namespace watergen {

struct RecordedFile {
    std::string path; // relative to the output directory
    uint64_t size = 0;
    std::string digest; // file_digest()
};

struct BuildRecord {
    std::string key;
    size_t variants = 0, shaders = 0;
    std::vector<RecordedFile> files; // sorted by path
};

// xxHash64 over the bytes of the material file (none: the built-in material) and of each scene
// file with its file name, and `options` (mode, freeze: whatever else shapes the output), as 16
// hex digits; nullopt when a file cannot be read (loading it reports why).
std::optional<std::string> build_inputs_hash(const std::string& material_path,
                                             const std::vector<std::string>& scene_paths,
                                             const std::string& options);

// XXH3-128 of the running executable (/proc/self/exe), computed once: a rebuilt watergen whose
// version string did not change still makes every record stale.
const std::string& executable_digest();

// The record's key: the inputs hash, the shard, toolchain_fingerprint() and executable_digest().
std::string record_key(const std::string& inputs_hash, const std::string& shard);

// The file in `cache` that holds the record of the output directory `out` (resolved).
std::filesystem::path record_file(const BuildCache& cache, const std::filesystem::path& out);

BuildRecord make_record(const std::string& key, size_t variants, size_t shaders,
                        const FileMap& files);
std::string record_text(const BuildRecord& record);
// Its parts: the head (key, counts) and one file's line.
std::string record_head(const std::string& key, size_t variants, size_t shaders, size_t files);
std::string record_line(const RecordedFile& file);
// nullopt for anything that is not a well-formed record (then the build simply runs).
std::optional<BuildRecord> parse_record(const std::string& text);
std::optional<BuildRecord> read_record(const std::filesystem::path& file);
// Writes the record atomically (temporary + rename); a record that cannot be written only
// costs the next build its shortcut, so failures are ignored.
void store_record(const std::filesystem::path& file, const BuildRecord& record);
// Every file of an output, sorted by path, handed over one at a time.
using ListFiles = std::function<void(const std::function<void(const RecordedFile&)>&)>;
// The same record written one file at a time (`count` files), for an output too large to list
// in memory.
void store_record(const std::filesystem::path& file, const std::string& key, size_t variants,
                  size_t shaders, size_t count, const ListFiles& files);

// Whether the record names every file the manifest `manifest` names, and manifest.json: a
// record that lost a line cannot vouch for an output that lost that file.
bool record_covers_manifest(const BuildRecord& record, const std::string& manifest);
// The same for the manifest in `manifest`, read one variant at a time.
bool record_covers_manifest(const BuildRecord& record, std::FILE* manifest);

// Whether every recorded file is in `out`, a regular file of its size and digest (read on
// `threads` workers; 0: all cores). No link is followed on the way: not `out`, not a directory
// inside it, not a file.
bool outputs_intact(const std::filesystem::path& out, const BuildRecord& record, unsigned threads);

} // namespace watergen
