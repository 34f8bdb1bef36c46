// Builds spread over machines: `watergen build --shard I/N` builds the variants whose key hashes
// to slice I of N, and `watergen merge` puts the N outputs together into exactly the output one
// build writes (the same manifest bytes, the same files). Each shard's output carries shard.json:
// which shard it is, what it was built from (the inputs hash and toolchain versions, which must
// agree across shards), the shape hash of each of its variants and every file with its size
// and hash. Two variants of a scene with the same shape are one shader; a single build writes
// it once, under the first key, and so does the merge, whichever shards the two landed in.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "watergen/pipeline/cache/build_cache.h"
#include "watergen/pipeline/jobs/parallel_build.h"
#include "watergen/pipeline/output/json_document.h"
#include "watergen/pipeline/record/build_record.h"

namespace watergen {

struct Shard {
    unsigned index = 0, count = 0; // 1-based; count 0: not sharded
    bool sharded() const { return count > 0; }
};

// "I/N" with 1 <= I <= N; nullopt and *error (what was given, what is expected) otherwise.
std::optional<Shard> parse_shard(const std::string& text, std::string* error);
// "I/N", or "" when not sharded.
std::string shard_text(const Shard& shard);
// Whether the job with this key belongs to the shard: xxHash64 of the key, modulo N, is I - 1.
bool in_shard(const Shard& shard, const std::string& key);

// The shard.json a shard's output carries (its `files` are the output's, manifest included),
// written one shape and one file at a time: the head when made, a job's shape per add() as the
// build's batches finish, and the file list at end().
class ShardJsonWriter {
  public:
    ShardJsonWriter(const Shard& shard, const std::string& inputs_hash, size_t variants,
                    WriteText write);
    void add(const BuildJob& job, const JobResult& r);
    void end(const ListFiles& files);

  private:
    WriteText write_; // before doc_, which writes through it
    JsonDocumentWriter doc_;
};

constexpr const char* kShardFile = "shard.json";

struct MergeResult {
    std::string error;         // non-empty: nothing was written
    bool write_failed = false; // the shards were fine, the output could not be written
    std::string warning;       // the output is written; its build record is not
    size_t shards = 0, variants = 0, files = 0;
};

// Merges the outputs of shards 1..N of one build into `out` (replaced as a whole, as a build
// replaces it). Refused, with nothing written: a directory without shard.json, shards of
// different inputs or toolchains, a shard missing or given twice, a variant in two shards, a
// file that does not match its recorded size and hash. With an enabled `cache`, then stores
// the build record one build of the same inputs into `out` stores (build_record.h), so that
// the next `watergen build` of those inputs into `out` is a no-op. Shards are merged in memory
// that does not grow with their variants: their lists go to spill files beside the merged tree
// (streamed_merge.cpp for a permutations build; a modes build's shaders are held, its variants
// spilled).
MergeResult merge_shards(const std::filesystem::path& out,
                         const std::vector<std::filesystem::path>& shards,
                         const BuildCache& cache = {});

} // namespace watergen
