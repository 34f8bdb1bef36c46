#include "watergen/pipeline/sharded_build.h"

#include <algorithm>
#include <map>
#include <set>

#include <nlohmann/json.hpp>
#include <xxhash.h>

#include "watergen/pipeline/build_output.h"
#include "watergen/pipeline/build_record.h"
#include "watergen/pipeline/manifest_files.h"
#include "watergen/pipeline/output_target.h"
#include "watergen/pipeline/output_writer.h"
#include "watergen/pipeline/safe_read.h"
#include "watergen/pipeline/shard_file.h"

namespace watergen {

namespace fs = std::filesystem;
using OJson = nlohmann::ordered_json;

namespace {

constexpr size_t kMaxShardFileBytes = size_t(512) << 20;
constexpr size_t kMaxOutputFileBytes = size_t(1) << 30;

// A shard's output, read and verified against its shard.json.
struct ShardOutput {
    fs::path dir;
    ShardFile meta;
    OJson manifest;
    FileMap files; // manifest.json and shard.json left out
};

// Reads `dir` as a shard's output; "" or why not.
std::string read_shard(const fs::path& dir, ShardOutput& s) {
    s.dir = dir;
    const std::string where = dir.string() + ": ";
    const SafeRead meta = read_regular_file(dir / kShardFile, kMaxShardFileBytes);
    if (!meta.bytes)
        return where + (meta.missing
                            ? "no shard.json; expected the output of watergen build --shard I/N"
                            : "shard.json " + meta.why);
    std::string why;
    auto parsed = parse_shard_file(*meta.bytes, &why);
    if (!parsed) return where + why;
    s.meta = std::move(*parsed);
    std::set<std::string> listed;
    for (const ListedFile& f : s.meta.files) {
        const SafeRead r =
            read_regular_file(dir / f.path, std::min<uint64_t>(f.size, kMaxOutputFileBytes));
        if (!r.bytes || r.bytes->size() != f.size || file_digest(*r.bytes) != f.digest)
            return where + f.path + " does not match the size and hash shard.json records" +
                   (r.bytes ? "" : " (" + (r.missing ? std::string("missing") : r.why) + ")");
        listed.insert(f.path);
        if (f.path == "manifest.json")
            s.manifest = OJson::parse(*r.bytes, nullptr, false);
        else
            s.files.emplace(f.path, std::move(*r.bytes));
    }
    if (std::string bad = check_shard_manifest(s.manifest, s.meta, listed); !bad.empty())
        return where + bad;
    return "";
}

// The manifest without its variants: the material, the space, the scenes.
std::string header_of(const OJson& manifest) {
    OJson h = manifest;
    h.erase("variants");
    return h.dump();
}

// The shards, checked to be 1..N of one build; "" or why not.
std::string check_set(const std::vector<ShardOutput>& shards) {
    const ShardOutput& first = shards.front();
    std::map<unsigned, const ShardOutput*> by_index;
    for (const ShardOutput& s : shards) {
        const std::string both = s.dir.string() + " and " + first.dir.string();
        if (s.meta.toolchain != first.meta.toolchain)
            return both + " were built by different watergen or toolchain versions ('" +
                   s.meta.toolchain + "' and '" + first.meta.toolchain +
                   "'); expected one for every shard";
        if (s.meta.inputs != first.meta.inputs ||
            header_of(s.manifest) != header_of(first.manifest))
            return both + " were built from different inputs (material, scenes or options); "
                          "expected shards of one build";
        if (s.meta.shard.count != first.meta.shard.count)
            return both + " are shards of " + std::to_string(s.meta.shard.count) + " and of " +
                   std::to_string(first.meta.shard.count) + "; expected shards of one build";
        if (auto [it, fresh] = by_index.emplace(s.meta.shard.index, &s); !fresh)
            return "shard " + shard_text(s.meta.shard) +
                   " is given twice: " + it->second->dir.string() + " and " + s.dir.string();
    }
    for (unsigned i = 1; i <= first.meta.shard.count; ++i)
        if (!by_index.count(i))
            return "shard " + shard_text({i, first.meta.shard.count}) +
                   " is missing; expected all of 1/" + std::to_string(first.meta.shard.count) +
                   " .. " + shard_text({first.meta.shard.count, first.meta.shard.count});
    return "";
}

// The fields of a manifest entry that name where its files are.
const std::set<std::string> kOutputFields = {"same_as",    "directory",          "files",
                                             "reflection", "spirv_instructions", "passes"};

// `own` pointing at the files of `builder` (same shader), as manifest_json writes such an entry.
OJson as_same(const OJson& own, const OJson& builder) {
    OJson v = OJson::object();
    for (const auto& [name, value] : own.items())
        if (!kOutputFields.count(name)) v[name] = value;
    v["same_as"] = builder["key"];
    for (const auto& [name, value] : builder.items())
        if (kOutputFields.count(name) && name != "same_as") v[name] = value;
    return v;
}

// Why OUT may not be the merge's output beside these shards: it is one, holds one or lies
// inside one (links resolved); "" when apart from all.
std::string out_apart_from_shards(const fs::path& out, const std::vector<fs::path>& dirs) {
    std::error_code ec;
    const fs::path o = fs::weakly_canonical(normal_output_path(out), ec);
    for (const fs::path& d : dirs) {
        const fs::path shard = fs::weakly_canonical(normal_output_path(d), ec);
        const std::string both = out.string() + " and the shard " + d.string();
        if (o == shard)
            return "the output directory " + out.string() + " is the shard " + d.string() +
                   "; expected an output directory apart from every shard";
        if (path_holds(o, shard))
            return "the output directory " + out.string() + " holds the shard " + d.string() +
                   ", which the merge would delete with the old output; expected an output "
                   "directory apart from every shard";
        if (path_holds(shard, o))
            return "the output directory " + out.string() + " lies inside the shard " + d.string() +
                   "; expected an output directory apart from every shard";
    }
    return "";
}

// The merged manifest: every scene holds as many variants as its header counts (a shard that
// lost a variant falls short), and every file the manifest names is among the merged files.
std::string check_merged(const OJson& manifest, const FileMap& files) {
    std::map<std::string, size_t> held;
    for (const OJson& v : manifest["variants"])
        ++held[v.value("scene", "")];
    for (const OJson& scene : manifest.value("scenes", OJson::array())) {
        const std::string name = scene.value("name", "");
        const OJson count = scene.value("variants", OJson());
        if (!count.is_number_unsigned() || count.get<size_t>() != held[name])
            return "scene " + name + ": the shards hold " + std::to_string(held[name]) +
                   " variants, the build's manifest counts " + count.dump() +
                   "; expected every variant of the build in one of the shards";
        held.erase(name);
    }
    if (!held.empty())
        return "variants of scene " + held.begin()->first +
               ", which the build's manifest does not name";
    for (const OJson& v : manifest["variants"]) {
        std::vector<std::string> paths;
        if (std::string why = named_files(v, paths); !why.empty()) return why;
        for (const std::string& p : paths)
            if (!files.count(p))
                return "the merged manifest would name " + p + ", which no shard holds";
    }
    return "";
}

} // namespace

std::string shard_json(const Shard& shard, const std::string& inputs_hash,
                       const std::vector<BuildJob>& jobs, const std::vector<JobResult>& results,
                       size_t variants, const FileMap& files) {
    OJson j;
    j["watergen_shard"] = 1;
    j["index"] = shard.index;
    j["count"] = shard.count;
    j["toolchain"] = toolchain_fingerprint();
    j["inputs"] = inputs_hash;
    j["variants"] = variants;
    OJson shapes = OJson::array();
    for (size_t i = 0; i < jobs.size(); ++i)
        shapes.push_back({jobs[i].scene, job_key(jobs[i]), results[i].shape_hash});
    j["shapes"] = shapes;
    OJson list = OJson::array();
    for (const auto& [path, bytes] : files)
        list.push_back({path, bytes.size(), file_digest(bytes)});
    j["files"] = list;
    return j.dump(1) + "\n";
}

MergeResult merge_shards(const fs::path& out, const std::vector<fs::path>& dirs,
                         const BuildCache& cache) {
    MergeResult m;
    if (dirs.empty()) {
        m.error = "no shard directories; expected the outputs of watergen build --shard 1/N .. N/N";
        return m;
    }
    // Refused before anything is read: the merge replaces OUT whole, so a shard at, above or
    // below it would be lost with the old tree, or would be read while being replaced.
    if (m.error = out_apart_from_shards(out, dirs); !m.error.empty()) return m;
    if (const OutputTarget t = check_output_target(out); !t.ok()) {
        m.error = out.string() + ": " + t.error;
        return m;
    }
    std::vector<ShardOutput> shards(dirs.size());
    for (size_t i = 0; i < dirs.size(); ++i)
        if (m.error = read_shard(dirs[i], shards[i]); !m.error.empty()) return m;
    if (m.error = check_set(shards); !m.error.empty()) return m;

    // Every variant once, sorted by (scene, key) as a build sorts them.
    std::map<std::pair<std::string, std::string>, std::pair<const OJson*, const ShardOutput*>> all;
    for (const ShardOutput& s : shards)
        for (const OJson& v : s.manifest["variants"]) {
            const std::pair<std::string, std::string> id{v.value("scene", ""), v.value("key", "")};
            if (!s.meta.shapes.count(id)) {
                m.error = s.dir.string() + ": variant " + id.first + "/" + id.second +
                          " has no shape in shard.json";
                return m;
            }
            if (auto [it, fresh] = all.emplace(id, std::make_pair(&v, &s)); !fresh) {
                m.error = "variant " + id.first + "/" + id.second + " is in both " +
                          it->second.second->dir.string() + " and " + s.dir.string();
                return m;
            }
        }
    // The first key of each shape of a scene is built; the others point at it.
    std::map<std::pair<std::string, std::string>, const OJson*> first; // (scene, shape)
    std::set<std::string> dropped;                                     // directories
    FileMap files;
    OJson variants = OJson::array();
    for (const auto& [id, where] : all) {
        const auto& [entry, shard] = where;
        const auto [it, fresh] =
            first.emplace(std::make_pair(id.first, shard->meta.shapes.at(id)), entry);
        if (fresh) {
            variants.push_back(*entry);
            continue;
        }
        if (!entry->contains("same_as")) dropped.insert(entry->value("directory", "") + "/");
        variants.push_back(as_same(*entry, *it->second));
    }
    for (const ShardOutput& s : shards)
        for (const auto& [path, bytes] : s.files) {
            if (path == kShardFile) continue;
            const size_t slash = path.find('/', path.find('/') + 1);
            if (slash != std::string::npos && dropped.count(path.substr(0, slash + 1))) continue;
            files[path] = bytes;
        }
    OJson manifest = shards.front().manifest;
    manifest["variants"] = variants;
    if (m.error = check_merged(manifest, files); !m.error.empty()) return m;
    files["manifest.json"] = manifest.dump(2) + "\n";
    if (auto e = publish_output(out, files)) {
        m.error = *e;
        m.write_failed = true;
        return m;
    }
    m.shards = shards.size();
    m.variants = variants.size();
    m.files = files.size();
    // What one unsharded build of these inputs records (a permutations build: a shader per
    // variant).
    if (cache.enabled())
        store_record(
            record_file(cache, out),
            make_record(record_key(shards.front().meta.inputs, ""), m.variants, m.variants, files));
    return m;
}

} // namespace watergen
