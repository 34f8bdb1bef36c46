#include "watergen/pipeline/shards/sharded_build.h"
#include "watergen/pipeline/record/shaders_header.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <sys/stat.h>
#include <tuple>

#include <nlohmann/json.hpp>
#include <xxhash.h>

#include "watergen/pipeline/manifest/caustics_pass_build.h"
#include "watergen/pipeline/manifest/manifest.h"
#include "watergen/pipeline/manifest/manifest_files.h"
#include "watergen/pipeline/output/json_document.h"
#include "watergen/pipeline/output/output_target.h"
#include "watergen/pipeline/output/output_writer.h"
#include "watergen/pipeline/output/safe_read.h"
#include "watergen/pipeline/output/spill_file.h"
#include "watergen/pipeline/record/build_record.h"
#include "watergen/pipeline/record/staged_tree.h"
#include "watergen/pipeline/shards/shard_file.h"
#include "watergen/runtime/manifest_schema.h"

#include "merge_parts.h"

namespace watergen {

namespace fs = std::filesystem;
using OJson = nlohmann::ordered_json;
namespace mk = manifest_schema;

namespace {

// Where the merge keeps the variants of the shards' manifests (compact text) while it reads
// them: a spill file in the staging directory, so memory holds an index, not documents.
class Spool {
  public:
    using Ref = SpillFile::Ref;
    explicit Spool(const fs::path& dir) : file_(dir, ".merge-spool") {}
    bool ok() const { return file_.ok(); }
    std::optional<Ref> put(const std::string& text) { return file_.append(text); }
    OJson get(Ref r) const {
        std::string text;
        if (!file_.read(r.offset, r.size, text) || text.size() != r.size) return OJson();
        return OJson::parse(text, nullptr, false);
    }

  private:
    SpillFile file_;
};

// A variant of a shard's manifest, as the merge keeps it.
struct SpooledVariant {
    std::string scene, key;
    Spool::Ref entry;
    std::string directory; // its "directory"
    bool same_as = false;  // it points at another variant's files
};

// A modes build's shard output, checked against its shard.json: the manifest read one entry at
// a time into the spool, the other files checked for kind and size (their hashes when copied).
struct ShardOutput : ShardHead {
    bool modes = false;               // its manifest names a mode
    std::vector<SpooledVariant> jobs; // its shaders
    // Its variants, in the manifest's order (scene, key): per variant its scene, key and where
    // the spool holds its entry (offset, size), in a spill file; their count per scene.
    std::unique_ptr<SpillFile> served;
    std::map<std::string, size_t> served_per_scene;
    size_t served_count = 0;
};
constexpr size_t kServedFields = 4;

// Reads `dir` as a shard's output, its served variants' list in `scratch`; "" or why not.
std::string read_shard(const fs::path& dir, const fs::path& scratch, ShardOutput& s, Spool& spool) {
    s.dir = dir;
    const std::string where = dir.string() + ": ";
    std::string why;
    std::FILE* meta_in = open_shard_json(dir, &why);
    if (!meta_in) return why;
    auto parsed = read_shard_file(meta_in, &why);
    std::fclose(meta_in);
    if (!parsed) return where + why;
    s.meta = std::move(*parsed);
    std::optional<ListedFile> listed_manifest;
    for (size_t i = 0; i < s.meta.files.size(); ++i) {
        const ListedFile f = s.meta.files[i];
        if (f.path == "manifest.json")
            listed_manifest = f;
        else if (std::string fault = listed_file_fault(dir, f); !fault.empty())
            return fault;
    }
    std::FILE* in = open_shard_manifest(dir, listed_manifest, &why);
    if (!in) return why;
    s.head = OJson::object();
    bool has_variants = false, has_shaders = false;
    std::set<std::string> shaders; // the directories of its shaders
    std::string bad;
    EntryOrder order;
    s.served = std::make_unique<SpillFile>(scratch, ".merge-served");
    if (!s.served->ok()) return "cannot write the merge's spool in " + scratch.string();
    // A variant: its entry in the spool, listed in order (the shards' lists are merged in one
    // pass).
    auto served = [&](const OJson& v) {
        const std::string scene = v[mk::variant::kScene], key = v[mk::variant::kKey];
        if (bad = order.next(scene, key); !bad.empty()) return false;
        const auto ref = spool.put(v.dump());
        if (!ref || !s.served->append(spill_record(
                        {scene, key, std::to_string(ref->offset), std::to_string(ref->size)}))) {
            bad = "cannot write the merge's spool beside the output";
            return false;
        }
        ++s.served_per_scene[scene];
        ++s.served_count;
        return true;
    };
    auto spooled = [&](const OJson& v) -> std::optional<SpooledVariant> {
        const auto ref = spool.put(v.dump());
        if (!ref) {
            bad = "cannot write the merge's spool beside the output";
            return std::nullopt;
        }
        return SpooledVariant{v[mk::shader::kScene], v[mk::shader::kKey], *ref,
                              v.value(mk::output::kDirectory, ""), v.contains(mk::output::kSameAs)};
    };
    // A modes manifest names its mode, then its shaders, then the variants they draw.
    JsonDocumentReader reader{{mk::top::kVariants, mk::top::kShaders},
                              [&](const std::string& name, OJson&& value) {
                                  if (name == mk::top::kVariants || name == mk::top::kShaders)
                                      return false; // not a list
                                  s.modes = s.modes || name == mk::top::kMode;
                                  s.head[name] = std::move(value);
                                  return true;
                              },
                              [&](const std::string& array, OJson&& v) {
                                  const bool is_served = array == mk::top::kVariants;
                                  if (!s.modes)
                                      bad = "a permutations manifest in a merge of modes shards";
                                  else if (is_served && !has_shaders)
                                      bad = "a modes manifest's variants before its shaders";
                                  else
                                      bad = is_served ? check_served_variant(v, s.meta, shaders)
                                                      : check_shard_variant(v, s.meta);
                                  if (!bad.empty()) return false;
                                  if (is_served) return served(v);
                                  auto entry = spooled(v);
                                  if (!entry) return false;
                                  shaders.insert(entry->directory);
                                  s.jobs.push_back(std::move(*entry));
                                  return true;
                              },
                              [&](const std::string& array) {
                                  (array == mk::top::kVariants ? has_variants : has_shaders) = true;
                              }};
    const JsonReadEnd end = read_json_document(in, reader, nullptr);
    std::fclose(in);
    if (!bad.empty()) return where + bad;
    if (end != JsonReadEnd::Done || !has_variants || !has_shaders)
        return where + "no manifest.json of a build among the files shard.json lists";
    if (std::string count = check_variant_count(s.jobs.size(), s.served_count, s.meta);
        !count.empty())
        return where + count;
    s.header = s.head.dump();
    return "";
}

// A modes build's variant whose shader another shard's shader of the same shape replaced, drawn
// by that one, as one build writes it: its "shader" and its frozen modules' directory.
void moved_to_its_shader(OJson& entry, const std::map<std::string, std::string>& moved) {
    const auto to = moved.find(entry.value(mk::variant::kShader, ""));
    if (to == moved.end()) return;
    entry[mk::variant::kShader] = to->second;
    if (auto frozen = entry.find(mk::variant::kFrozen);
        frozen != entry.end() && frozen->is_object())
        for (auto path = frozen->begin(); path != frozen->end(); ++path)
            if (path->is_string())
                *path = to->second + path->get<std::string>().substr(to->first.size());
}

} // namespace

namespace {

OJson shard_head(const Shard& shard, const std::string& inputs_hash, size_t variants) {
    OJson head;
    head["watergen_shard"] = 1;
    head["index"] = shard.index;
    head["count"] = shard.count;
    head["toolchain"] = toolchain_fingerprint();
    head["inputs"] = inputs_hash;
    head["variants"] = variants;
    return head;
}

} // namespace

ShardJsonWriter::ShardJsonWriter(const Shard& shard, const std::string& inputs_hash,
                                 size_t variants, WriteText write)
    : write_(std::move(write)), doc_(shard_head(shard, inputs_hash, variants), write_) {
    doc_.begin_array("shapes");
}

void ShardJsonWriter::add(const BuildJob& job, const JobResult& r) {
    doc_.element({job.scene, job_key(job), r.shape_hash});
}

void ShardJsonWriter::end(const ListFiles& files) {
    doc_.end_array();
    doc_.begin_array("files");
    files([&](const RecordedFile& f) { doc_.element({f.path, f.size, f.digest}); });
    doc_.end_array();
    doc_.end();
}

namespace {

// Whether the shard in `dir` is of a specialized or branching build: its manifest's head names a
// mode. False when it cannot tell (the streamed merge then reports what is wrong).
bool modes_shard(const fs::path& dir) {
    SafeRead seen;
    std::FILE* in = open_regular_stream(dir / "manifest.json", seen);
    if (!in) return false;
    bool modes = false;
    const JsonDocumentReader reader{{mk::top::kVariants, mk::top::kShaders},
                                    [&](const std::string& name, OJson&&) {
                                        modes = modes || name == mk::top::kMode;
                                        return true;
                                    },
                                    [](const std::string&, OJson&&) { return false; }};
    read_json_document(in, reader, nullptr);
    std::fclose(in);
    return modes;
}

// The merge of a modes build's shards: the shaders held (as spooled entries, keys and
// directories), the variants merged from the shards' lists one at a time.
MergeResult merge_modes(const fs::path& out, const std::vector<fs::path>& dirs,
                        const BuildCache& cache) {
    MergeResult m;
    fs::path target;
    const std::unique_ptr<StagedTree> tree = start_merge(out, dirs, target, m);
    if (!tree) return m;
    Spool spool(tree->dir());
    if (!spool.ok()) {
        m.error = "cannot create the merge's spool in " + tree->dir().string();
        m.write_failed = true;
        return m;
    }
    std::vector<ShardOutput> shards(dirs.size());
    for (size_t i = 0; i < dirs.size(); ++i)
        if (m.error = read_shard(dirs[i], tree->dir(), shards[i], spool); !m.error.empty())
            return m;
    std::vector<const ShardHead*> heads;
    for (const ShardOutput& shard : shards)
        heads.push_back(&shard);
    if (m.error = check_set(heads); !m.error.empty()) return m;

    // Every shader once, sorted by (scene, key) as a build sorts them.
    using Id = std::pair<std::string, std::string>;
    using Held = std::map<Id, std::pair<const SpooledVariant*, const ShardOutput*>>;
    Held all;
    auto gather = [&](Held& into, std::vector<SpooledVariant> ShardOutput::*entries,
                      const char* what) {
        for (const ShardOutput& s : shards)
            for (const SpooledVariant& v : s.*entries) {
                const Id id{v.scene, v.key};
                if (auto [it, fresh] = into.emplace(id, std::make_pair(&v, &s)); !fresh) {
                    m.error = std::string(what) + " " + id.first + "/" + id.second +
                              " is in both " + it->second.second->dir.string() + " and " +
                              s.dir.string();
                    return false;
                }
            }
        return true;
    };
    if (!gather(all, &ShardOutput::jobs, "shader")) return m;
    // The first key of each shape of a scene is built; the others point at it. A modes build's
    // shader replaced so moves its variants, and their frozen modules, to the one built.
    std::map<Id, const SpooledVariant*> first;  // (scene, shape)
    std::vector<const SpooledVariant*> builder; // per job of `all`, in order
    std::set<std::string> dropped;              // directories
    std::map<std::string, std::string> moved;   // a dropped shader's directory -> the built one's
    std::map<std::string, size_t> held;
    for (const auto& [id, where] : all) {
        const auto& [v, shard] = where;
        const auto [it, fresh] = first.emplace(Id(id.first, shard->meta.shapes.at(id)), v);
        builder.push_back(fresh ? v : it->second);
        if (!fresh && !v->same_as) {
            dropped.insert(v->directory);
            moved[v->directory] = it->second->directory;
        }
    }
    for (const ShardOutput& s : shards)
        for (const auto& [scene, count] : s.served_per_scene)
            held[scene] += count;
    if (m.error = check_counts(shards.front().head, held); !m.error.empty()) return m;
    auto listed = [&](const std::string& path) {
        return std::any_of(shards.begin(), shards.end(),
                           [&](const auto& s) { return s.meta.lists(path); });
    };
    // Where a shard's file goes in the merged output; "" for none.
    auto destination = [&](const std::string& path) -> std::string {
        const std::string dir = directory_of(path);
        if (dir.empty() || !dropped.count(dir)) return path;
        const auto to = moved.find(dir);
        const std::string rest = path.substr(dir.size());
        const bool frozen = rest.find("/frozen/") != std::string::npos;
        return to != moved.end() && frozen ? to->second + rest : "";
    };
    auto merged = [&](const std::string& path) {
        if (destination(path) == path && listed(path)) return true;
        for (const auto& [from, to] : moved)
            if (directory_of(path) == to && listed(from + path.substr(to.size()))) return true;
        return false;
    };

    // The merged manifest, one entry at a time; every file it names among the merged files.
    StagedStream manifest = tree->stream("manifest.json");
    const WriteText write = [&](std::string_view piece) { manifest.write(piece); };
    JsonDocumentWriter doc(shards.front().head, write);
    auto write_entry = [&](const OJson& entry) {
        std::vector<std::string> paths;
        if (m.error = named_files(entry, paths); !m.error.empty()) return false;
        for (const std::string& p : paths)
            if (!merged(p)) {
                m.error = "the merged manifest would name " + p + ", which no shard holds";
                return false;
            }
        doc.element(entry);
        return true;
    };
    auto write_jobs = [&] {
        size_t k = 0;
        for (const auto& [id, where] : all) {
            OJson entry = spool.get(where.first->entry);
            if (builder[k] != where.first) entry = as_same(entry, spool.get(builder[k]->entry));
            ++k;
            if (!write_entry(entry)) return false;
        }
        return true;
    };
    // The variants: the shards' lists (each in (scene, key) order) merged k ways.
    auto write_served = [&] {
        std::vector<SpillReader> lists;
        for (const ShardOutput& s : shards)
            lists.emplace_back(*s.served, 0, s.served->end());
        RecordMerge merge(std::move(lists), kServedFields);
        std::string scene, key, dir;
        while (merge.next()) {
            const auto& f = merge.fields(); // scene, key, offset, size
            const std::string& from = shards[merge.list()].dir.string();
            if (!dir.empty() && f[0] == scene && f[1] == key) {
                m.error = "variant " + scene + "/" + key + " is in both " + dir + " and " + from;
                return false;
            }
            scene = f[0];
            key = f[1];
            dir = from;
            OJson entry = spool.get({std::stoull(f[2]), std::stoull(f[3])});
            moved_to_its_shader(entry, moved);
            if (!write_entry(entry)) return false;
        }
        if (merge.failed()) {
            m.error = "cannot read the merge's spool in " + tree->dir().string();
            m.write_failed = true;
            return false;
        }
        return true;
    };
    doc.begin_array(mk::top::kShaders);
    if (!write_jobs()) return m;
    doc.end_array();
    doc.begin_array(mk::top::kVariants);
    if (!write_served()) return m;
    doc.end_array();
    doc.end();
    if (auto e = manifest.close()) {
        m.error = *e;
        m.write_failed = true;
        return m;
    }

    // The shards' files, each checked against its size and hash as it is copied.
    std::set<std::string> passes;
    for (const ShardOutput& s : shards) {
        std::vector<std::pair<ListedFile, std::string>> files;
        for (size_t i = 0; i < s.meta.files.size(); ++i) {
            ListedFile f = s.meta.files[i];
            if (f.path == "manifest.json" || f.path == kShardFile) continue;
            std::string to = destination(f.path);
            if (!to.empty() && first_copy(f.path, passes)) files.emplace_back(std::move(f), to);
        }
        if (!copy_listed(*tree, s.dir, files, m)) return m;
    }
    m.shards = shards.size();
    size_t variants = 0;
    for (const ShardOutput& s : shards)
        variants += s.served_count;
    finish_merge(*tree, out, target, shards.front().meta.inputs, variants, all.size(), cache, m);
    return m;
}

} // namespace

MergeResult merge_shards(const fs::path& out, const std::vector<fs::path>& dirs,
                         const BuildCache& cache) {
    // A modes build's jobs are shaders, its variants listed across them: its own merge.
    if (!dirs.empty() && modes_shard(dirs.front())) return merge_modes(out, dirs, cache);
    return merge_streamed(out, dirs, cache);
}

} // namespace watergen
