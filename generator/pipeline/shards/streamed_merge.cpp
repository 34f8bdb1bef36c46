// `watergen merge` of a permutations build's shards in memory that does not grow with them. Each
// shard is read once into spill files beside the merged tree: shard.json's shapes in the
// file's order, its files as one sorted run, and the manifest's entries (each checked against
// the shape shard.json names in the same place, its files matched against the shard's list in
// sorted runs). The shards' entries, each shard's sorted by (scene, key) as a build writes
// them, are then merged k ways into the manifest one entry at a time; the first of each shape
// of a scene is built and the others point at it, as one build writes them. What is held is a
// 16-byte hash per shape of the current scene and the directories dropped for another shard's
// same shader.
#include <algorithm>
#include <array>
#include <cerrno>
#include <map>
#include <mutex>
#include <set>
#include <sys/stat.h>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "watergen/pipeline/cache/build_cache.h"
#include "watergen/pipeline/jobs/parallel_build.h"
#include "watergen/pipeline/manifest/caustics_pass_build.h"
#include "watergen/pipeline/manifest/manifest_files.h"
#include "watergen/pipeline/output/file_runs.h"
#include "watergen/pipeline/output/json_document.h"
#include "watergen/pipeline/output/output_writer.h"
#include "watergen/pipeline/output/safe_read.h"
#include "watergen/pipeline/output/spill_file.h"
#include "watergen/runtime/manifest_schema.h"

#include "merge_parts.h"

namespace watergen {

namespace fs = std::filesystem;
using OJson = nlohmann::ordered_json;
namespace mk = manifest_schema;

namespace {

// Names held in memory before they are sorted into a run.
constexpr size_t kNamesPerRun = size_t(1) << 16;
// Files copied at once (read, checked and written on every core).
constexpr size_t kFilesPerCopy = 4096;

// Shapes and directories keyed by 16 bytes, as the build's ledger keys them.
using Hash128 = BuildLedger::Hash128;
using HashOf = BuildLedger::HashOf;
Hash128 hash_of(std::string_view text) {
    return BuildLedger::hash_of(text);
}

// Paths gathered into sorted runs (FileRuns) and listed back in order, duplicates and all.
class SortedNames {
  public:
    explicit SortedNames(const fs::path& scratch) : runs_(scratch) {}
    // False if a run could not be written.
    bool add(std::string path) {
        held_.push_back(std::move(path));
        return held_.size() < kNamesPerRun || spill();
    }
    // The names in path order; `failed` if a run could not be read back.
    FileRuns::Cursor cursor() {
        std::sort(held_.begin(), held_.end());
        next_ = 0;
        return runs_.cursor([this](RunRecord& r) {
            if (next_ == held_.size()) return false;
            r.path = held_[next_++];
            return true;
        });
    }

  private:
    bool spill() {
        std::sort(held_.begin(), held_.end());
        FileRuns::Run run = runs_.begin_run();
        for (const std::string& p : held_)
            run.add(p, 0, {});
        held_.clear();
        return !run.finish();
    }
    FileRuns runs_;
    std::vector<std::string> held_;
    size_t next_ = 0;
};

// The first of `names` (sorted) that `listed` (sorted) lacks; "" when it has them all.
std::string first_missing(FileRuns::Cursor names, FileRuns::Cursor listed, bool& failed) {
    RunRecord name, file;
    bool have = listed.next(file);
    std::string missing;
    while (missing.empty() && names.next(name)) {
        while (have && file.path < name.path)
            have = listed.next(file);
        if (!have || file.path != name.path) missing = name.path;
    }
    failed = names.failed() || listed.failed();
    return missing;
}

// A permutations shard read for the merge: its head, and its lists in spill files.
struct StreamedShard : ShardHead {
    std::unique_ptr<SpillFile> shapes, index, texts;
    std::unique_ptr<FileRuns> files; // shard.json's files: one sorted run
    size_t entries = 0;
};

// An entry as the index keeps it: scene, key, shape, directory, same_as ("1"/"0"), and where its
// text is in `texts` (offset, size).
constexpr size_t kIndexFields = 7;

// Reads `dir` as a permutations shard's output into `s`, its spill files in `scratch`; "" or
// why not.
std::string read_streamed(const fs::path& dir, const fs::path& scratch, StreamedShard& s) {
    s.dir = dir;
    const std::string where = dir.string() + ": ";
    s.shapes = std::make_unique<SpillFile>(scratch, ".merge-shapes");
    s.index = std::make_unique<SpillFile>(scratch, ".merge-index");
    s.texts = std::make_unique<SpillFile>(scratch, ".merge-texts");
    s.files = std::make_unique<FileRuns>(scratch);
    const std::string no_spool = "cannot write the merge's spool in " + scratch.string();
    if (!s.shapes->ok() || !s.index->ok() || !s.texts->ok()) return no_spool;
    std::string why;
    std::FILE* meta_in = open_shard_json(dir, &why);
    if (!meta_in) return why;
    std::optional<ListedFile> listed_manifest;
    size_t shapes = 0;
    bool spooled = true;
    FileRuns::Run run = s.files->begin_run();
    const ShardSink sink{
        [&](const std::string& scene, const std::string& key, const std::string& shape) {
            spooled = spooled && s.shapes->append(spill_record({scene, key, shape}));
            ++shapes;
            return std::string();
        },
        [&](const ListedFile& f) {
            uint64_t high = 0, low = 0;
            parse_file_digest(f.digest, high, low); // checked by the reader
            run.add(f.path, f.size, {low, high});
            if (f.path == "manifest.json") {
                listed_manifest = f;
                return std::string();
            }
            return listed_file_fault(dir, f); // kind and size now; the hash when copied
        }};
    auto parsed = read_shard_file(meta_in, sink, &why);
    std::fclose(meta_in);
    if (!parsed) return why.rfind(dir.string(), 0) == 0 ? why : where + why;
    if (run.finish() || !spooled) return no_spool;
    s.meta = std::move(*parsed);
    std::FILE* in = open_shard_manifest(dir, listed_manifest, &why);
    if (!in) return why;
    // Each entry beside the shape shard.json names in its place, its files gathered to be
    // matched against the shard's list, spooled with its shape.
    SpillReader shape_reader(*s.shapes, 0, s.shapes->end());
    std::vector<std::string> shape;
    SortedNames named(scratch);
    std::string bad;
    EntryOrder order;
    bool has_variants = false, has_shaders = false;
    auto entry = [&](OJson&& v) {
        const bool next_shape = shape_reader.next(shape, 3);
        bad = check_variant_entry(
            v, s.meta.shard,
            [&](const std::string& scene, const std::string& key) {
                return next_shape && shape[0] == scene && shape[1] == key;
            },
            [&](const std::string& path) {
                spooled = named.add(path) && spooled;
                return true;
            });
        if (!bad.empty()) return false;
        const std::string scene = v[mk::variant::kScene], key = v[mk::variant::kKey];
        if (bad = order.next(scene, key); !bad.empty()) return false;
        const auto text = s.texts->append(v.dump());
        spooled = spooled && text &&
                  s.index->append(
                      spill_record({scene, key, shape[2], v.value(mk::output::kDirectory, ""),
                                    v.contains(mk::output::kSameAs) ? "1" : "0",
                                    std::to_string(text->offset), std::to_string(text->size)}));
        ++s.entries;
        return spooled;
    };
    const JsonDocumentReader reader{{mk::top::kVariants, mk::top::kShaders},
                                    [&](const std::string& name, OJson&& value) {
                                        if (name == mk::top::kVariants || name == mk::top::kShaders)
                                            return false; // not a list
                                        if (name == mk::top::kMode)
                                            bad = "a modes manifest in a merge "
                                                  "of permutations shards";
                                        s.head[name] = std::move(value);
                                        return bad.empty();
                                    },
                                    [&](const std::string& array, OJson&& v) {
                                        if (array == mk::top::kShaders) {
                                            bad = "a permutations manifest with shaders";
                                            return false;
                                        }
                                        return entry(std::move(v));
                                    },
                                    [&](const std::string& array) {
                                        (array == mk::top::kVariants ? has_variants : has_shaders) =
                                            true;
                                    }};
    s.head = OJson::object();
    const JsonReadEnd end = read_json_document(in, reader, nullptr);
    std::fclose(in);
    if (!bad.empty()) return where + bad;
    if (!spooled || shape_reader.failed()) return no_spool;
    if (end != JsonReadEnd::Done || !has_variants || has_shaders)
        return where + "no manifest.json of a build among the files shard.json lists";
    if (s.entries != shapes || s.entries != s.meta.variants)
        return where + "manifest.json holds " + std::to_string(s.entries) + " variants in " +
               std::to_string(s.entries) + " shaders, shard.json names " + std::to_string(shapes) +
               " shaders and counts " + std::to_string(s.meta.variants) +
               " variants; expected one count";
    bool failed = false;
    const std::string missing = first_missing(named.cursor(), s.files->cursor(), failed);
    if (failed) return no_spool;
    if (!missing.empty())
        return where + "manifest.json names " + missing + ", which shard.json does not list";
    s.header = s.head.dump();
    return "";
}

// The text of an entry of `shard`: where its index record puts it (offset, size).
OJson entry_text(const StreamedShard& shard, const std::string& offset, const std::string& size) {
    std::string t;
    const uint64_t bytes = std::stoull(size);
    if (!shard.texts->read(std::stoull(offset), bytes, t) || t.size() != bytes) return OJson();
    return OJson::parse(t, nullptr, false);
}

} // namespace

MergeResult merge_streamed(const fs::path& out, const std::vector<fs::path>& dirs,
                           const BuildCache& cache) {
    MergeResult m;
    fs::path target;
    const std::unique_ptr<StagedTree> tree = start_merge(out, dirs, target, m);
    if (!tree) return m;
    std::vector<StreamedShard> shards(dirs.size());
    std::vector<const ShardHead*> heads;
    for (size_t i = 0; i < dirs.size(); ++i) {
        if (m.error = read_streamed(dirs[i], tree->dir(), shards[i]); !m.error.empty()) return m;
        heads.push_back(&shards[i]);
    }
    if (m.error = check_set(heads); !m.error.empty()) return m;

    // The shards' entries merged in (scene, key) order, each written as one build writes it.
    std::vector<SpillReader> lists;
    for (const StreamedShard& s : shards)
        lists.emplace_back(*s.index, 0, s.index->end());
    RecordMerge merge(std::move(lists), kIndexFields);
    StagedStream manifest = tree->stream("manifest.json");
    const WriteText write = [&](std::string_view piece) { manifest.write(piece); };
    JsonDocumentWriter doc(shards.front().head, write);
    doc.begin_array(mk::top::kVariants);
    std::map<std::string, size_t> held; // variants per scene
    std::string scene, last_key, last_dir;
    // Per shape of the current scene, the entry that is built: its shard's cursor and text place.
    std::unordered_map<Hash128, std::pair<const StreamedShard*, std::array<std::string, 2>>, HashOf>
        first;
    std::unordered_set<Hash128, HashOf> dropped; // directories another shard's shader replaces
    SortedNames named(tree->dir());
    bool spooled = true;
    while (merge.next()) {
        const StreamedShard& shard = shards[merge.list()];
        const std::vector<std::string>& f = merge.fields();
        if (f[0] == scene && f[1] == last_key) {
            m.error = "variant " + f[0] + "/" + f[1] + " is in both " + last_dir + " and " +
                      shard.dir.string();
            return m;
        }
        if (f[0] != scene) first.clear(); // a shape is one shader within a scene only
        scene = f[0];
        last_key = f[1];
        last_dir = shard.dir.string();
        OJson entry = entry_text(shard, f[5], f[6]);
        const auto [it, fresh] =
            first.try_emplace(hash_of(f[2]), &shard, std::array<std::string, 2>{f[5], f[6]});
        if (!fresh) {
            // Another shard built this shader first: this entry points at it, and its own
            // files (if it built them) are not copied.
            const auto& [built, place] = it->second;
            entry = as_same(entry, entry_text(*built, place[0], place[1]));
            if (f[4] == "0") dropped.insert(hash_of(f[3]));
        }
        ++held[scene];
        std::vector<std::string> paths;
        if (m.error = named_files(entry, paths); !m.error.empty()) return m;
        for (std::string& p : paths)
            spooled = named.add(std::move(p)) && spooled;
        doc.element(entry);
    }
    doc.end_array();
    doc.end();
    if (merge.failed()) spooled = false;
    if (m.error = check_counts(shards.front().head, held); !m.error.empty()) return m;
    if (auto e = manifest.close(); e || !spooled) {
        m.error = e ? *e : "cannot write the merge's spool in " + tree->dir().string();
        m.write_failed = true;
        return m;
    }

    // The shards' files, each checked against its size and hash as it is copied, a slice at a
    // time.
    std::set<std::string> passes;
    for (const StreamedShard& s : shards) {
        FileRuns::Cursor listed = s.files->cursor();
        std::vector<std::pair<ListedFile, std::string>> slice;
        RunRecord r;
        for (bool more = true; more;) {
            slice.clear();
            while (slice.size() < kFilesPerCopy && (more = listed.next(r))) {
                if (r.path == "manifest.json" || r.path == kShardFile) continue;
                if (dropped.count(hash_of(directory_of(r.path)))) continue;
                if (!first_copy(r.path, passes)) continue;
                slice.push_back(
                    {{r.path, r.size, digest_text(r.digest.high64, r.digest.low64)}, r.path});
            }
            if (!copy_listed(*tree, s.dir, slice, m)) return m;
        }
        if (listed.failed()) {
            m.error = "cannot read the merge's spool in " + tree->dir().string();
            m.write_failed = true;
            return m;
        }
    }
    // Every file the merged manifest names is among the merged files.
    FileRuns merged(tree->dir());
    FileRuns::Run all = merged.begin_run();
    tree->for_each_file([&](const RecordedFile& f) { all.add(f.path, f.size, {}); });
    bool failed = static_cast<bool>(all.finish());
    const std::string missing =
        failed ? std::string() : first_missing(named.cursor(), merged.cursor(), failed);
    if (failed || !tree->failure().empty()) {
        m.error = "cannot read the merge's spool in " + tree->dir().string();
        m.write_failed = true;
        return m;
    }
    if (!missing.empty()) {
        m.error = "the merged manifest would name " + missing + ", which no shard holds";
        return m;
    }
    m.shards = shards.size();
    size_t variants = 0;
    for (const auto& [name, count] : held)
        variants += count;
    finish_merge(*tree, out, target, shards.front().meta.inputs, variants, variants, cache, m);
    return m;
}

} // namespace watergen
