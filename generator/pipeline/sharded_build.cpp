#include "watergen/pipeline/sharded_build.h"

#include <algorithm>
#include <map>
#include <set>

#include <nlohmann/json.hpp>
#include <xxhash.h>

#include "watergen/pipeline/build_output.h"
#include "watergen/pipeline/output_writer.h"
#include "watergen/pipeline/safe_read.h"

namespace watergen {

namespace fs = std::filesystem;
using OJson = nlohmann::ordered_json;

namespace {

constexpr size_t kMaxShardFileBytes = size_t(512) << 20;
constexpr size_t kMaxOutputFileBytes = size_t(1) << 30;

// "<digits>" as a number of at most 9 digits.
std::optional<unsigned> small_number(const std::string& text) {
    if (text.empty() || text.size() > 9 ||
        text.find_first_not_of("0123456789") != std::string::npos)
        return std::nullopt;
    return static_cast<unsigned>(std::stoul(text));
}

// A shard's output, read and verified against its shard.json.
struct ShardOutput {
    fs::path dir;
    Shard shard;
    std::string toolchain, inputs;
    size_t variants = 0;
    std::map<std::pair<std::string, std::string>, std::string> shapes; // (scene, key) -> shape
    OJson manifest;
    FileMap files; // manifest.json and shard.json left out
};

bool is_uint(const OJson& j) {
    return j.is_number_unsigned();
}

// Reads `dir` as a shard's output; "" or why not.
std::string read_shard(const fs::path& dir, ShardOutput& s) {
    s.dir = dir;
    const std::string where = dir.string() + ": ";
    const SafeRead meta = read_regular_file(dir / kShardFile, kMaxShardFileBytes);
    if (!meta.bytes)
        return where + (meta.missing
                            ? "no shard.json; expected the output of watergen build --shard I/N"
                            : "shard.json " + meta.why);
    const OJson j = OJson::parse(*meta.bytes, nullptr, false);
    const bool shaped =
        j.is_object() && j.value("watergen_shard", 0) == 1 && is_uint(j.value("index", OJson())) &&
        is_uint(j.value("count", OJson())) && j.value("toolchain", OJson()).is_string() &&
        j.value("inputs", OJson()).is_string() && is_uint(j.value("variants", OJson())) &&
        j.value("shapes", OJson()).is_array() && j.value("files", OJson()).is_array();
    if (!shaped) return where + "shard.json is not one watergen build --shard wrote";
    s.shard = {j["index"].get<unsigned>(), j["count"].get<unsigned>()};
    if (s.shard.index < 1 || s.shard.index > s.shard.count)
        return where + "shard.json names shard " + std::to_string(s.shard.index) + "/" +
               std::to_string(s.shard.count) + "; expected I/N with 1 <= I <= N";
    s.toolchain = j["toolchain"];
    s.inputs = j["inputs"];
    s.variants = j["variants"];
    for (const auto& shape : j["shapes"]) {
        if (!shape.is_array() || shape.size() != 3 || !shape[0].is_string() ||
            !shape[1].is_string() || !shape[2].is_string())
            return where + "shard.json: a shape is not [scene, key, hash]";
        s.shapes[{shape[0], shape[1]}] = shape[2];
    }
    for (const auto& f : j["files"]) {
        if (!f.is_array() || f.size() != 3 || !f[0].is_string() || !is_uint(f[1]) ||
            !f[2].is_string() || !is_plain_relative_path(f[0]))
            return where + "shard.json: a file is not [relative path, size, hash]";
        const std::string path = f[0];
        const size_t size = f[1].get<size_t>();
        const SafeRead r = read_regular_file(dir / path, std::min(size, kMaxOutputFileBytes));
        if (!r.bytes || r.bytes->size() != size || file_digest(*r.bytes) != f[2])
            return where + path + " does not match the size and hash shard.json records" +
                   (r.bytes ? "" : " (" + (r.missing ? std::string("missing") : r.why) + ")");
        if (path == "manifest.json")
            s.manifest = OJson::parse(*r.bytes, nullptr, false);
        else
            s.files.emplace(path, std::move(*r.bytes));
    }
    if (!s.manifest.is_object() || !s.manifest.value("variants", OJson()).is_array())
        return where + "no manifest.json of a build among the files shard.json lists";
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
        if (s.toolchain != first.toolchain)
            return both + " were built by different watergen or toolchain versions ('" +
                   s.toolchain + "' and '" + first.toolchain + "'); expected one for every shard";
        if (s.inputs != first.inputs || header_of(s.manifest) != header_of(first.manifest))
            return both + " were built from different inputs (material, scenes or options); "
                          "expected shards of one build";
        if (s.shard.count != first.shard.count)
            return both + " are shards of " + std::to_string(s.shard.count) + " and of " +
                   std::to_string(first.shard.count) + "; expected shards of one build";
        if (auto [it, fresh] = by_index.emplace(s.shard.index, &s); !fresh)
            return "shard " + shard_text(s.shard) + " is given twice: " + it->second->dir.string() +
                   " and " + s.dir.string();
    }
    for (unsigned i = 1; i <= first.shard.count; ++i)
        if (!by_index.count(i))
            return "shard " + shard_text({i, first.shard.count}) +
                   " is missing; expected all of 1/" + std::to_string(first.shard.count) + " .. " +
                   shard_text({first.shard.count, first.shard.count});
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

} // namespace

std::optional<Shard> parse_shard(const std::string& text, std::string* error) {
    const size_t slash = text.find('/');
    const auto i = small_number(text.substr(0, slash));
    const auto n = slash == std::string::npos ? std::nullopt : small_number(text.substr(slash + 1));
    if (i && n && *i >= 1 && *i <= *n) return Shard{*i, *n};
    if (error)
        *error = "'" + text + "': expected I/N, shard I of N with 1 <= I <= N (e.g. 1/4 .. 4/4)";
    return std::nullopt;
}

std::string shard_text(const Shard& shard) {
    return shard.sharded() ? std::to_string(shard.index) + "/" + std::to_string(shard.count) : "";
}

bool in_shard(const Shard& shard, const std::string& key) {
    return !shard.sharded() || XXH64(key.data(), key.size(), 0) % shard.count == shard.index - 1;
}

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

MergeResult merge_shards(const fs::path& out, const std::vector<fs::path>& dirs) {
    MergeResult m;
    if (dirs.empty()) {
        m.error = "no shard directories; expected the outputs of watergen build --shard 1/N .. N/N";
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
            if (!s.shapes.count(id)) {
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
            first.emplace(std::make_pair(id.first, shard->shapes.at(id)), entry);
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
    files["manifest.json"] = manifest.dump(2) + "\n";
    if (auto e = publish_output(out, files)) {
        m.error = *e;
        m.write_failed = true;
        return m;
    }
    m.shards = shards.size();
    m.variants = variants.size();
    m.files = files.size();
    return m;
}

} // namespace watergen
