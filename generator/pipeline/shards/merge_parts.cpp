#include "merge_parts.h"

#include <algorithm>
#include <cerrno>
#include <mutex>
#include <sys/stat.h>
#include <tuple>

#include <xxhash.h>

#include "watergen/pipeline/cache/build_cache.h"
#include "watergen/pipeline/jobs/parallel_build.h"
#include "watergen/pipeline/manifest/caustics_pass_build.h"
#include "watergen/pipeline/output/output_target.h"
#include "watergen/pipeline/output/safe_read.h"
#include "watergen/pipeline/record/build_record.h"
#include "watergen/pipeline/record/shaders_header.h"
#include "watergen/runtime/manifest_schema.h"

namespace watergen {

namespace fs = std::filesystem;
using OJson = nlohmann::ordered_json;
namespace mk = manifest_schema;

namespace {

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

} // namespace

std::string mismatch(const fs::path& dir, const ListedFile& f, const std::string& detail) {
    return dir.string() + ": " + f.path + " does not match the size and hash shard.json records" +
           detail;
}

namespace {

// The XXH3-128 digest and size of what `in` holds from its start.
std::pair<std::string, uint64_t> stream_digest(std::FILE* in) {
    std::unique_ptr<XXH3_state_t, XXH_errorcode (*)(XXH3_state_t*)> state(XXH3_createState(),
                                                                          XXH3_freeState);
    XXH3_128bits_reset(state.get());
    std::vector<char> buffer(size_t(1) << 16);
    uint64_t size = 0;
    for (size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), in)) > 0; size += n)
        XXH3_128bits_update(state.get(), buffer.data(), n);
    const XXH128_hash_t h = XXH3_128bits_digest(state.get());
    return {digest_text(h.high64, h.low64), size};
}

} // namespace

std::string listed_file_fault(const fs::path& dir, const ListedFile& f) {
    struct stat st {};
    if (::lstat((dir / f.path).c_str(), &st) != 0)
        return mismatch(dir, f, errno == ENOENT ? " (missing)" : "");
    if (!S_ISREG(st.st_mode) || static_cast<uint64_t>(st.st_size) != f.size)
        return mismatch(
            dir, f, S_ISREG(st.st_mode) ? "" : std::string(" (is ") + file_kind(st.st_mode) + ")");
    return "";
}

std::FILE* open_shard_json(const fs::path& dir, std::string* why) {
    SafeRead meta;
    std::FILE* in = open_regular_stream(dir / kShardFile, meta);
    if (!in)
        *why = dir.string() + ": " +
               (meta.missing ? "no shard.json; expected the output of watergen build --shard I/N"
                             : "shard.json " + meta.why);
    return in;
}

std::FILE* open_shard_manifest(const fs::path& dir, const std::optional<ListedFile>& listed,
                               std::string* why) {
    if (!listed) {
        *why = dir.string() + ": no manifest.json of a build among the files shard.json lists";
        return nullptr;
    }
    SafeRead seen;
    std::FILE* in = open_regular_stream(dir / "manifest.json", seen);
    if (!in) {
        *why =
            mismatch(dir, *listed, " (" + (seen.missing ? std::string("missing") : seen.why) + ")");
        return nullptr;
    }
    // Hashed in one pass, then read again one variant at a time by the caller.
    const auto [digest, size] = stream_digest(in);
    std::rewind(in);
    if (size != listed->size || digest != listed->digest) {
        std::fclose(in);
        *why = mismatch(dir, *listed, "");
        return nullptr;
    }
    return in;
}

namespace {

// Copies the shard's file `f` to `to` in `tree` if its bytes match the size and hash listed;
// "" or why not, `wrote` when the shard was fine and the tree could not take it.
std::string copy_one(StagedTree& tree, const fs::path& dir, const ListedFile& f,
                     const std::string& to, bool& wrote) {
    wrote = false;
    const SafeRead r = read_regular_file(dir / f.path, f.size);
    if (!r.bytes || r.bytes->size() != f.size || file_digest(*r.bytes) != f.digest)
        return mismatch(dir, f,
                        r.bytes ? "" : " (" + (r.missing ? std::string("missing") : r.why) + ")");
    if (auto e = tree.write(to, *r.bytes)) {
        wrote = true;
        return *e;
    }
    return "";
}

} // namespace

bool copy_listed(StagedTree& tree, const fs::path& dir,
                 const std::vector<std::pair<ListedFile, std::string>>& files, MergeResult& m) {
    std::mutex lock;
    std::string first;
    bool write_failed = false;
    parallel_for(files.size(), 0, [&](size_t i) {
        bool wrote = false;
        const std::string why = copy_one(tree, dir, files[i].first, files[i].second, wrote);
        if (why.empty()) return;
        std::lock_guard<std::mutex> guard(lock);
        if (first.empty()) first = why, write_failed = wrote;
    });
    if (first.empty()) return true;
    m.error = first;
    m.write_failed = write_failed;
    return false;
}

std::string directory_of(const std::string& path) {
    const size_t slash = path.find('/', path.find('/') + 1);
    return slash == std::string::npos ? std::string() : path.substr(0, slash);
}

bool first_copy(const std::string& path, std::set<std::string>& copied) {
    return path.rfind(std::string(kPassesDirectory) + "/", 0) != 0 || copied.insert(path).second;
}

std::string check_set(const std::vector<const ShardHead*>& heads) {
    const ShardHead& first = *heads.front();
    std::map<unsigned, const ShardHead*> by_index;
    for (const ShardHead* h : heads) {
        const ShardHead& s = *h;
        const std::string both = s.dir.string() + " and " + first.dir.string();
        if (s.meta.toolchain != first.meta.toolchain)
            return both + " were built by different watergen or toolchain versions ('" +
                   s.meta.toolchain + "' and '" + first.meta.toolchain +
                   "'); expected one for every shard";
        if (s.meta.inputs != first.meta.inputs || s.header != first.header)
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

const std::set<std::string> kOutputFields = {
    mk::output::kSameAs,     mk::output::kDirectory,         mk::output::kFiles,
    mk::output::kReflection, mk::output::kSpirvInstructions, mk::variant::kPasses};

OJson as_same(const OJson& own, const OJson& builder) {
    OJson v = OJson::object();
    for (const auto& [name, value] : own.items())
        if (!kOutputFields.count(name)) v[name] = value;
    v[mk::output::kSameAs] = builder[mk::variant::kKey];
    for (const auto& [name, value] : builder.items())
        if (kOutputFields.count(name) && name != mk::output::kSameAs) v[name] = value;
    return v;
}

// A shard that lost a variant falls short; no variant may be of a scene the head does not name.
std::string check_counts(const OJson& head, std::map<std::string, size_t> held) {
    for (const OJson& scene : head.value(mk::top::kScenes, OJson::array())) {
        const std::string name = scene.value(mk::scene::kName, "");
        const OJson count = scene.value(mk::scene::kVariants, OJson());
        if (!count.is_number_unsigned() || count.get<size_t>() != held[name])
            return "scene " + name + ": the shards hold " + std::to_string(held[name]) +
                   " variants, the build's manifest counts " + count.dump() +
                   "; expected every variant of the build in one of the shards";
        held.erase(name);
    }
    if (!held.empty())
        return "variants of scene " + held.begin()->first +
               ", which the build's manifest does not name";
    return "";
}

std::unique_ptr<StagedTree> start_merge(const fs::path& out, const std::vector<fs::path>& dirs,
                                        fs::path& target, MergeResult& m) {
    if (dirs.empty()) {
        m.error = "no shard directories; expected the outputs of watergen build --shard 1/N .. N/N";
        return nullptr;
    }
    // Refused before anything is read: the merge replaces OUT whole, so a shard at, above or
    // below it would be lost with the old tree, or would be read while being replaced.
    if (m.error = out_apart_from_shards(out, dirs); !m.error.empty()) return nullptr;
    const OutputTarget checked = check_output_target(out);
    if (!checked.ok()) {
        m.error = out.string() + ": " + checked.error;
        return nullptr;
    }
    target = checked.path;
    // The merged tree is written beside OUT as it is made, and replaces OUT at the end.
    std::string error;
    std::unique_ptr<StagedTree> tree = StagedTree::open(target, &error);
    if (!tree) {
        m.error = error;
        m.write_failed = true;
    }
    return tree;
}

void finish_merge(StagedTree& tree, const fs::path& out, const fs::path& target,
                  const std::string& inputs, size_t variants, size_t shaders,
                  const BuildCache& cache, MergeResult& m) {
    // The merged build's C++ header, as one build of the same inputs writes it.
    if (auto e = write_shaders_header(tree)) {
        m.error = *e;
        m.write_failed = true;
        return;
    }
    // Checked again: the merge took a while.
    if (const OutputTarget again = check_output_target(out); !again.ok()) {
        m.error = out.string() + ": " + again.error;
        return;
    }
    if (auto e = tree.commit(target)) {
        m.error = *e;
        m.write_failed = true;
        return;
    }
    m.variants = variants;
    m.files = tree.count();
    // What one unsharded build of these inputs records.
    if (cache.enabled())
        if (auto why =
                store_record(record_file(cache, out), record_key(inputs, ""), variants, shaders,
                             m.files, [&](const std::function<void(const RecordedFile&)>& each) {
                                 tree.for_each_file(each);
                             }))
            m.warning = record_not_stored(*why);
}

RecordMerge::RecordMerge(std::vector<SpillReader> lists, size_t fields) : n_(fields) {
    for (SpillReader& r : lists)
        cursors_.push_back({std::move(r), {}});
    for (size_t k = 0; k < cursors_.size(); ++k)
        if (cursors_[k].reader.next(cursors_[k].fields, n_)) heap_.push_back(k);
    std::make_heap(heap_.begin(), heap_.end(), [this](size_t a, size_t b) { return later(a, b); });
}

bool RecordMerge::later(size_t a, size_t b) const {
    const auto& x = cursors_[a].fields;
    const auto& y = cursors_[b].fields;
    return std::tie(y[0], y[1]) < std::tie(x[0], x[1]);
}

bool RecordMerge::next() {
    auto cmp = [this](size_t a, size_t b) { return later(a, b); };
    if (list_ != SIZE_MAX && cursors_[list_].reader.next(cursors_[list_].fields, n_)) {
        heap_.push_back(list_);
        std::push_heap(heap_.begin(), heap_.end(), cmp);
    }
    if (heap_.empty()) return false;
    std::pop_heap(heap_.begin(), heap_.end(), cmp);
    list_ = heap_.back();
    heap_.pop_back();
    fields_ = cursors_[list_].fields;
    return true;
}

bool RecordMerge::failed() const {
    return std::any_of(cursors_.begin(), cursors_.end(),
                       [](const Cursor& c) { return c.reader.failed(); });
}

std::string EntryOrder::next(const std::string& scene, const std::string& key) {
    if (any_ && std::tie(scene, key) <= std::tie(scene_, key_))
        return "variant " + scene + "/" + key +
               " of manifest.json is out of order or twice; expected the variants sorted by "
               "scene and key, each once";
    any_ = true;
    scene_ = scene;
    key_ = key;
    return "";
}

} // namespace watergen
