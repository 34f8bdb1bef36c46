// What `watergen merge` reads of one shard's output, trusting none of it: shard.json parsed into
// its fields (every one checked for type and range), and the shard's manifest checked against
// it: each variant (a modes build: each shader) in the shard's key range, exactly the ones
// shard.json names, every file the manifest names listed in shard.json, plain and inside its
// variant's (or shader's) directory.
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "watergen/pipeline/output/path_parts.h"
#include "watergen/pipeline/shards/sharded_build.h"

namespace watergen {

// file_digest()'s text back into its two halves; false for anything else.
bool parse_file_digest(const std::string& text, uint64_t& high, uint64_t& low);

struct ListedFile {
    std::string path; // plain relative (is_plain_relative_path)
    uint64_t size = 0;
    std::string digest; // file_digest()
};

// shard.json's files, sorted by path, in about 40 bytes each (a merge holds every shard's list:
// as strings a file took about 550): the path as PathParts, the digest as its 16 bytes.
class ListedFiles {
  public:
    // Appends `f`, which the caller has checked comes after the last; false (nothing added)
    // when its digest is not file_digest()'s text, 32 lowercase hexadecimal digits.
    bool push_back(const ListedFile& f);
    size_t size() const { return entries_.size(); }
    bool empty() const { return entries_.empty(); }
    ListedFile operator[](size_t i) const;
    bool contains(const std::string& path) const;

  private:
    struct Entry {
        PathParts::Path path;
        uint64_t size, high, low;
    };
    PathParts paths_;
    std::vector<Entry> entries_;
};

struct ShardFile {
    Shard shard;
    std::string toolchain, inputs;
    size_t variants = 0;
    std::map<std::pair<std::string, std::string>, std::string> shapes; // (scene, key) -> shape
    ListedFiles files;                                                 // sorted by path
    bool lists(const std::string& path) const { return files.contains(path); }
};

// shard.json's text as a ShardFile; nullopt and *why (what is wrong, what was expected). Read
// one shape and one file at a time: no document of the whole is made.
std::optional<ShardFile> parse_shard_file(const std::string& text, std::string* why);
// The same from an open file, read as it goes (a merge never holds shard.json's text).
std::optional<ShardFile> read_shard_file(std::FILE* in, std::string* why);

// Where a reader that holds neither list puts shard.json's shapes and files, in the file's order
// (each file checked for form, order and digest first); a non-empty return is the fault that
// stops the read.
struct ShardSink {
    std::function<std::string(const std::string& scene, const std::string& key,
                              const std::string& shape)>
        shape;
    std::function<std::string(const ListedFile& file)> file;
};
// shard.json's head (shard, toolchain, inputs, variants) as a ShardFile without shapes or
// files: those went to `sink`.
std::optional<ShardFile> read_shard_file(std::FILE* in, const ShardSink& sink, std::string* why);

// One variant of a permutations shard's manifest (or one shader of a modes shard's) against its
// shard.json (a merge reads the manifest one entry at a time): in the shard's key range, among
// its shapes, every file it names listed; "" or why not.
std::string check_shard_variant(const nlohmann::ordered_json& variant, const ShardFile& shard);
// The same against a shard's head and two questions: is (scene, key) the shape shard.json names
// next (or at all), and is a path listed.
using HasShape = std::function<bool(const std::string& scene, const std::string& key)>;
std::string check_variant_entry(const nlohmann::ordered_json& variant, const Shard& shard,
                                const HasShape& has_shape,
                                const std::function<bool(const std::string&)>& lists);
// One variant of a modes shard's manifest: drawn by one of the shard's shaders (`shaders`, their
// directories), its frozen modules listed; "" or why not.
std::string check_served_variant(const nlohmann::ordered_json& variant, const ShardFile& shard,
                                 const std::set<std::string>& shaders);
// The number of shaders (variants, in a permutations build) and of variants the manifest held
// against shard.json's; "" or why not.
std::string check_variant_count(size_t jobs, size_t variants, const ShardFile& shard);
// The whole manifest: each entry, and their counts.
std::string check_shard_manifest(const nlohmann::ordered_json& manifest, const ShardFile& shard);

} // namespace watergen
