// What the two ways of `watergen merge` share (sharded_build.cpp: a modes build's shards, held;
// streamed_merge.cpp: a permutations build's, streamed): the checks that the shards are one
// build's, the merged entry of a variant whose shader another shard built, and the output's
// start and end. Internal to the pipeline library.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "watergen/pipeline/output/spill_file.h"
#include "watergen/pipeline/record/staged_tree.h"
#include "watergen/pipeline/shards/shard_file.h"
#include "watergen/pipeline/shards/sharded_build.h"

namespace watergen {

// A shard's output as both merges know it: where, shard.json's head, the manifest's head.
struct ShardHead {
    std::filesystem::path dir;
    ShardFile meta;              // a streamed merge's without shapes and files
    nlohmann::ordered_json head; // the manifest without its variants (and shaders)
    std::string header;          // head.dump(): shards of one build have the same
};

std::string mismatch(const std::filesystem::path& dir, const ListedFile& f,
                     const std::string& detail);
// A file shard.json lists (not the manifest) as the shard holds it: a regular file of its size
// ("" or the mismatch); its hash is checked when it is copied.
std::string listed_file_fault(const std::filesystem::path& dir, const ListedFile& f);
// The shard's shard.json opened; nullptr and *why (no shard.json, or why it cannot be read).
std::FILE* open_shard_json(const std::filesystem::path& dir, std::string* why);
// The shard's manifest.json opened once its size and hash are what shard.json lists
// (`listed`); nullptr and *why otherwise.
std::FILE* open_shard_manifest(const std::filesystem::path& dir,
                               const std::optional<ListedFile>& listed, std::string* why);
// Copies each of the shard's files (a file, and where it goes in `tree`) on every core if its
// bytes match the size and hash listed; false and m.error (m.write_failed when the shard was fine
// and the tree could not take one) at the first that does not.
bool copy_listed(StagedTree& tree, const std::filesystem::path& dir,
                 const std::vector<std::pair<ListedFile, std::string>>& files, MergeResult& m);
// Whether the merge copies this shard file of a companion pass: the passes are in every shard
// that needs them, copied once (`copied`: those so far). True for any other file.
bool first_copy(const std::string& path, std::set<std::string>& copied);
// The shards, checked to be 1..N of one build; "" or why not.
// A shard manifest's entries must come in (scene, key) order, each once: the shards' lists are
// merged in one pass. next() is "" for the next entry in order, else why not.
class EntryOrder {
  public:
    std::string next(const std::string& scene, const std::string& key);

  private:
    bool any_ = false;
    std::string scene_, key_;
};

// The shards' lists of records (spill files, each sorted by its first two fields: scene, key)
// merged k ways: each record in that order, with the list it came from.
class RecordMerge {
  public:
    RecordMerge(std::vector<SpillReader> lists, size_t fields);
    // Moves to the next record; false when every list is done (or one failed to read).
    bool next();
    const std::vector<std::string>& fields() const { return fields_; }
    size_t list() const { return list_; }
    bool failed() const; // a list could not be read back

  private:
    struct Cursor {
        SpillReader reader;
        std::vector<std::string> fields;
    };
    bool later(size_t a, size_t b) const;
    std::vector<Cursor> cursors_;
    std::vector<size_t> heap_;
    size_t n_;
    size_t list_ = SIZE_MAX; // the current record's list
    std::vector<std::string> fields_;
};

std::string check_set(const std::vector<const ShardHead*>& heads);
// The job directory a path of the output lies in (<scene>/<name>: its first two parts); "" for a
// file outside one.
std::string directory_of(const std::string& path);
// The fields of a manifest entry that name where its files are.
extern const std::set<std::string> kOutputFields;
// `own` pointing at the files of `builder` (same shader), as manifest_json writes such an entry.
nlohmann::ordered_json as_same(const nlohmann::ordered_json& own,
                               const nlohmann::ordered_json& builder);
// Every scene of the merged manifest's head holds as many variants as it counts; "" or why not.
std::string check_counts(const nlohmann::ordered_json& head, std::map<std::string, size_t> held);

// The merge's staging tree beside OUT once OUT may be replaced and lies apart from every shard
// (resolved into `target`); nullptr with m.error otherwise.
std::unique_ptr<StagedTree> start_merge(const std::filesystem::path& out,
                                        const std::vector<std::filesystem::path>& dirs,
                                        std::filesystem::path& target, MergeResult& m);
// The merge's end once its manifest and files are in the tree: the C++ header, OUT checked
// again, the swap, and (with a cache) the record one build of these inputs stores. m.error on
// failure.
void finish_merge(StagedTree& tree, const std::filesystem::path& out,
                  const std::filesystem::path& target, const std::string& inputs, size_t variants,
                  size_t shaders, const BuildCache& cache, MergeResult& m);

// merge_shards for the shards of a permutations build, holding no list that grows with them.
MergeResult merge_streamed(const std::filesystem::path& out,
                           const std::vector<std::filesystem::path>& dirs, const BuildCache& cache);

} // namespace watergen
