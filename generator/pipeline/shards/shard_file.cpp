#include "watergen/pipeline/shards/shard_file.h"

#include <algorithm>
#include <functional>

#include <fmt/format.h>
#include <xxhash.h>

#include "watergen/pipeline/manifest/manifest_files.h"
#include "watergen/pipeline/output/json_document.h"
#include "watergen/pipeline/output/output_writer.h"
#include "watergen/runtime/manifest_schema.h"

namespace watergen {

using OJson = nlohmann::ordered_json;
// The manifest's keys (shard.json's are its own, spelled here).
namespace mk = manifest_schema;

namespace {

// A shard lists its variants' files, 27.5 a variant of the full space: a 64th of its 3,502,080
// variants lists about 1.5 million, a 16th about 6 million. Far more is not a shard watergen
// wrote, and would only cost memory (about 45 bytes a file, ListedFiles).
constexpr size_t kMaxShardEntries = size_t(1) << 23;

bool is_uint(const OJson& j) {
    return j.is_number_unsigned();
}

bool is_string_triple(const OJson& j) {
    return j.is_array() && j.size() == 3 && j[0].is_string() && j[1].is_string();
}

bool starts_with(const std::string& s, const std::string& prefix) {
    return s.compare(0, prefix.size(), prefix) == 0;
}

// "<digits>" as a number of at most 9 digits.
std::optional<unsigned> small_number(const std::string& text) {
    if (text.empty() || text.size() > 9 ||
        text.find_first_not_of("0123456789") != std::string::npos)
        return std::nullopt;
    return static_cast<unsigned>(std::stoul(text));
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

bool parse_file_digest(const std::string& text, uint64_t& high, uint64_t& low) {
    if (text.size() != 32) return false;
    uint64_t halves[2] = {0, 0};
    for (size_t i = 0; i < 32; ++i) {
        const char c = text[i];
        const int v = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
        if (v < 0) return false;
        halves[i / 16] = halves[i / 16] << 4 | static_cast<uint64_t>(v);
    }
    high = halves[0];
    low = halves[1];
    return true;
}

namespace {

// shard.json read one shape and one file at a time (a 1/20 shard of the full space lists
// 829,842 files: its document would need several times the memory of its text).
std::optional<ShardFile> read_shard_document(const ReadJsonDocument& read, const ShardSink& sink,
                                             std::string* why) {
    std::string fault;
    auto fail = [&](const std::string& w) {
        if (fault.empty()) fault = w;
        return false;
    };
    const std::string not_ours = "shard.json is not one watergen build --shard wrote";
    auto too_many = [&] {
        return fail("shard.json lists more than " + std::to_string(kMaxShardEntries) +
                    " shapes or files; expected a shard of one build");
    };
    OJson head = OJson::object();
    ShardFile s;
    std::string previous;
    size_t shape_count = 0, file_count = 0;
    bool shapes = false, files = false;
    JsonDocumentReader reader{
        {"shapes", "files"},
        [&](const std::string& name, OJson&& value) {
            if (name == "shapes" || name == "files") return fail(not_ours); // not a list
            head[name] = std::move(value);
            return true;
        },
        [&](const std::string& array, OJson&& e) {
            if (array == "shapes") {
                if (shape_count++ >= kMaxShardEntries) return too_many();
                if (!is_string_triple(e) || !e[2].is_string())
                    return fail("shard.json: a shape is not [scene, key, hash]");
                if (std::string w = sink.shape(e[0], e[1], e[2]); !w.empty()) return fail(w);
                return true;
            }
            if (file_count++ >= kMaxShardEntries) return too_many();
            if (!e.is_array() || e.size() != 3 || !e[0].is_string() || !is_uint(e[1]) ||
                !e[2].is_string() || !is_plain_relative_path(e[0]))
                return fail("shard.json: a file is not [relative path, size, hash]");
            ListedFile file{e[0], e[1].get<uint64_t>(), e[2]};
            if (file_count > 1 && file.path <= previous)
                return fail("shard.json: " + file.path +
                            " out of order or twice; expected the "
                            "files sorted by path, each once");
            uint64_t high = 0, low = 0;
            if (!parse_file_digest(file.digest, high, low))
                return fail("shard.json: " + file.path + "'s hash '" + file.digest +
                            "' is not 32 lowercase hexadecimal digits (an XXH3-128 digest)");
            if (std::string w = sink.file(file); !w.empty()) return fail(w);
            previous = std::move(file.path);
            return true;
        },
        [&](const std::string& array) { (array == "shapes" ? shapes : files) = true; }};
    // Its head's members are numbers and strings, its entries triples of them.
    reader.max_depth = 2;
    reader.max_piece_values = 16;
    std::string malformed;
    const JsonReadEnd end = read(reader, &malformed);
    auto failed = [&](const std::string& w) -> std::optional<ShardFile> {
        if (why) *why = w;
        return std::nullopt;
    };
    if (!fault.empty()) return failed(fault);
    if (end != JsonReadEnd::Done) return failed(not_ours);
    const OJson& j = head;
    const bool shaped =
        is_uint(j.value("watergen_shard", OJson())) && j["watergen_shard"].get<uint64_t>() == 1 &&
        is_uint(j.value("index", OJson())) && is_uint(j.value("count", OJson())) &&
        j.value("toolchain", OJson()).is_string() && j.value("inputs", OJson()).is_string() &&
        is_uint(j.value("variants", OJson())) && shapes && files;
    if (!shaped) return failed(not_ours);
    if (j["index"].get<uint64_t>() > 1000000000 || j["count"].get<uint64_t>() > 1000000000)
        return failed("shard.json names a shard past 10^9; expected I/N of a build");
    s.shard = {j["index"].get<unsigned>(), j["count"].get<unsigned>()};
    if (s.shard.index < 1 || s.shard.index > s.shard.count)
        return failed("shard.json names shard " + std::to_string(s.shard.index) + "/" +
                      std::to_string(s.shard.count) + "; expected I/N with 1 <= I <= N");
    s.toolchain = j["toolchain"];
    s.inputs = j["inputs"];
    s.variants = j["variants"];
    return s;
}

} // namespace

namespace {

// shard.json read whole into a ShardFile: its shapes by (scene, key), its files in ListedFiles.
std::optional<ShardFile> read_shard_held(const ReadJsonDocument& read, std::string* why) {
    std::map<std::pair<std::string, std::string>, std::string> shapes;
    ListedFiles files;
    const ShardSink sink{
        [&](const std::string& scene, const std::string& key, const std::string& shape) {
            if (!shapes.emplace(std::make_pair(scene, key), shape).second)
                return "shard.json names variant " + scene + "/" + key + " twice";
            return std::string();
        },
        [&](const ListedFile& f) {
            files.push_back(f); // its digest checked already
            return std::string();
        }};
    std::optional<ShardFile> s = read_shard_document(read, sink, why);
    if (s) {
        s->shapes = std::move(shapes);
        s->files = std::move(files);
    }
    return s;
}

} // namespace

std::optional<ShardFile> parse_shard_file(const std::string& text, std::string* why) {
    return read_shard_held(
        [&](const JsonDocumentReader& r, std::string* w) { return read_json_document(text, r, w); },
        why);
}

std::optional<ShardFile> read_shard_file(std::FILE* in, std::string* why) {
    return read_shard_held(
        [&](const JsonDocumentReader& r, std::string* w) { return read_json_document(in, r, w); },
        why);
}

std::optional<ShardFile> read_shard_file(std::FILE* in, const ShardSink& sink, std::string* why) {
    return read_shard_document(
        [&](const JsonDocumentReader& r, std::string* w) { return read_json_document(in, r, w); },
        sink, why);
}

std::string check_variant_entry(const OJson& v, const Shard& shard, const HasShape& has_shape,
                                const std::function<bool(const std::string&)>& lists) {
    const OJson scene = v.value(mk::variant::kScene, OJson()),
                key = v.value(mk::variant::kKey, OJson());
    if (!scene.is_string() || !key.is_string())
        return "a variant of manifest.json has no scene and key";
    const std::string id = scene.get<std::string>() + "/" + key.get<std::string>();
    if (!has_shape(scene, key))
        return "variant " + id + " of manifest.json is not among shard.json's shapes";
    if (!in_shard(shard, key))
        return "variant " + id + " is not in shard " + shard_text(shard) +
               "'s key range (its key hashes to another shard)";
    std::vector<std::string> paths;
    if (std::string why = named_files(v, paths); !why.empty()) return "variant " + id + ": " + why;
    if (v.contains(mk::output::kDirectory) &&
        !starts_with(v[mk::output::kDirectory].get<std::string>(), scene.get<std::string>() + "/"))
        return "variant " + id + ": \"directory\" " + v[mk::output::kDirectory].dump() +
               " is outside its scene's directory " + scene.get<std::string>() + "/";
    for (const std::string& p : paths)
        if (!lists(p)) return "variant " + id + " names " + p + ", which shard.json does not list";
    return "";
}

std::string check_shard_variant(const OJson& v, const ShardFile& s) {
    return check_variant_entry(
        v, s.shard,
        [&](const std::string& scene, const std::string& key) {
            return s.shapes.count({scene, key}) > 0;
        },
        [&](const std::string& path) { return s.lists(path); });
}

std::string check_served_variant(const OJson& v, const ShardFile& s,
                                 const std::set<std::string>& shaders) {
    const OJson scene = v.value(mk::variant::kScene, OJson()),
                key = v.value(mk::variant::kKey, OJson()),
                shader = v.value(mk::variant::kShader, OJson());
    if (!scene.is_string() || !key.is_string() || !shader.is_string())
        return "a variant of manifest.json has no scene, key and shader";
    const std::string id = scene.get<std::string>() + "/" + key.get<std::string>();
    if (!shaders.count(shader))
        return "variant " + id + " is drawn by " + shader.dump() +
               ", which is no shader of the shard's manifest";
    std::vector<std::string> paths;
    if (std::string why = named_files(v, paths); !why.empty()) return "variant " + id + ": " + why;
    for (const std::string& p : paths)
        if (!s.lists(p))
            return "variant " + id + " names " + p + ", which shard.json does not list";
    return "";
}

std::string check_variant_count(size_t jobs, size_t variants, const ShardFile& s) {
    if (jobs != s.shapes.size() || variants != s.variants)
        return "manifest.json holds " + std::to_string(variants) + " variants in " +
               std::to_string(jobs) + " shaders, shard.json names " +
               std::to_string(s.shapes.size()) + " shaders and counts " +
               std::to_string(s.variants) + " variants; expected one count";
    return "";
}

bool ListedFiles::push_back(const ListedFile& f) {
    Entry e{{}, f.size, 0, 0};
    if (!parse_file_digest(f.digest, e.high, e.low)) return false;
    e.path = paths_.intern(f.path);
    entries_.push_back(e);
    return true;
}

ListedFile ListedFiles::operator[](size_t i) const {
    const Entry& e = entries_[i];
    // digest_text()'s form (build_cache.cpp, not in the fuzz target's sources).
    return {paths_.text(e.path), e.size, fmt::format("{:016x}{:016x}", e.high, e.low)};
}

bool ListedFiles::contains(const std::string& path) const {
    const auto it = std::lower_bound(
        entries_.begin(), entries_.end(), path,
        [&](const Entry& e, const std::string& p) { return paths_.compare(e.path, p) < 0; });
    return it != entries_.end() && paths_.compare(it->path, path) == 0;
}

std::string check_shard_manifest(const OJson& manifest, const ShardFile& s) {
    const bool modes = manifest.is_object() && manifest.contains(mk::top::kMode);
    if (!manifest.is_object() || !manifest.value(mk::top::kVariants, OJson()).is_array() ||
        (modes && !manifest.value(mk::top::kShaders, OJson()).is_array()))
        return "no manifest.json of a build among the files shard.json lists";
    const OJson& variants = manifest[mk::top::kVariants];
    const OJson& jobs = modes ? manifest[mk::top::kShaders] : variants;
    if (std::string why = check_variant_count(jobs.size(), variants.size(), s); !why.empty())
        return why;
    std::set<std::string> shaders;
    for (const OJson& v : jobs) {
        if (std::string why = check_shard_variant(v, s); !why.empty()) return why;
        if (modes) shaders.insert(v.value(mk::output::kDirectory, ""));
    }
    if (modes)
        for (const OJson& v : variants)
            if (std::string why = check_served_variant(v, s, shaders); !why.empty()) return why;
    return "";
}

} // namespace watergen
