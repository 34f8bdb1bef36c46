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

#include "watergen/pipeline/cache/build_cache.h"

namespace watergen {

struct RecordedFile {
    std::string path; // relative to the output directory
    uint64_t size = 0;
    std::string digest; // file_digest()
};

// A record's head: what it was made from, and what it counts.
struct RecordHead {
    std::string key;
    size_t variants = 0, shaders = 0, files = 0;
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
// A record read one file at a time: a build of the whole space records about 96 million files,
// more than a record read whole, or parsed into a BuildRecord, should take.
class RecordReader {
  public:
    // Reads the head from `in` (which the caller closes); ok() is false if it is malformed.
    explicit RecordReader(std::FILE* in);
    const RecordHead& head() const { return head_; }
    // The next file, paths strictly ascending; false at the end, or at a malformed line (ok()
    // then says which).
    bool next(RecordedFile& f);
    // Whether every line so far was well formed and, once next() returned false, the record was
    // whole: as many files as the head counts, and nothing after them.
    bool ok() const { return ok_; }

  private:
    std::FILE* in_;
    RecordHead head_;
    size_t read_ = 0;
    std::string last_;
    bool ok_ = true;
};

// nullopt for anything that is not a well-formed record (then the build simply runs).
std::optional<BuildRecord> parse_record(const std::string& text);
std::optional<BuildRecord> read_record(const std::filesystem::path& file);
// The record's head alone, nullopt if it is unreadable or malformed.
std::optional<RecordHead> read_record_head(const std::filesystem::path& file);
// The first component of every path the record names ("manifest.json", each scene's
// directory), one each: what output_target.h needs of a record, without holding it.
std::optional<std::vector<std::string>> record_top_entries(const std::filesystem::path& file);
// Writes the record atomically (temporary + rename). A record that cannot be written only
// costs the next build its shortcut: the caller says so as a warning (why, returned), and the
// output stands.
std::optional<std::string> store_record(const std::filesystem::path& file,
                                        const BuildRecord& record);
// Every file of an output, sorted by path, handed over one at a time.
using ListFiles = std::function<void(const std::function<void(const RecordedFile&)>&)>;
// The same record written one file at a time (`count` files), for an output too large to list
// in memory.
std::optional<std::string> store_record(const std::filesystem::path& file, const std::string& key,
                                        size_t variants, size_t shaders, size_t count,
                                        const ListFiles& files);
// The warning a build or merge gives when store_record fails.
std::string record_not_stored(const std::string& why);

// Whether the record names every file the manifest `manifest` names, and manifest.json: a
// record that lost a line cannot vouch for an output that lost that file.
bool record_covers_manifest(const BuildRecord& record, const std::string& manifest);
// The same for the manifest in `manifest`, read one variant at a time.
bool record_covers_manifest(const BuildRecord& record, std::FILE* manifest);
// The same for the record in `file`, read one file at a time: the manifest's names are sorted
// into runs in a spill file in `scratch` (file_runs.h) and matched against the record's sorted
// paths, so neither list is held. `also`: files the build writes that the manifest does not
// name (watergen_shaders.h, shard.json), which the record must name too.
bool record_covers_manifest(const std::filesystem::path& file, std::FILE* manifest,
                            const std::filesystem::path& scratch,
                            const std::vector<std::string>& also = {},
                            size_t names_per_run = size_t(1) << 16);

// Whether every recorded file is in `out`, a regular file of its size and digest (read on
// `threads` workers; 0: all cores). No link is followed on the way: not `out`, not a directory
// inside it, not a file.
bool outputs_intact(const std::filesystem::path& out, const BuildRecord& record, unsigned threads);
// The same for the record in `file`, read a slice of files at a time; false if it is malformed.
bool outputs_intact(const std::filesystem::path& out, const std::filesystem::path& file,
                    unsigned threads);

} // namespace watergen
