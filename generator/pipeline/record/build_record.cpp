#include "watergen/pipeline/record/build_record.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <fcntl.h>
#include <memory>
#include <set>
#include <sys/stat.h>
#include <unistd.h>

#include <xxhash.h>

#include "watergen/pipeline/jobs/parallel_build.h"
#include "watergen/pipeline/manifest/manifest_files.h"
#include "watergen/pipeline/output/file_runs.h"
#include "watergen/pipeline/output/output_target.h"
#include "watergen/pipeline/output/output_writer.h"
#include "watergen/pipeline/output/safe_read.h"

namespace watergen {

namespace fs = std::filesystem;

namespace {

// Description files are at most 4 MiB (json_source.h).
constexpr size_t kMaxInputBytes = size_t(8) << 20;

std::optional<std::string> read_whole(const fs::path& path, size_t limit) {
    const SafeRead r = read_regular_file(path, limit);
    return r.bytes;
}

// The XXH3-128 digest (file_digest()'s text) of the next `size` bytes of `fd`, read a buffer at a
// time: a whole-space build's manifest alone is tens of gigabytes. nullopt if they cannot all be
// read.
std::optional<std::string> digest_of(int fd, uint64_t size, std::vector<char>& buffer) {
    std::unique_ptr<XXH3_state_t, XXH_errorcode (*)(XXH3_state_t*)> state(XXH3_createState(),
                                                                          XXH3_freeState);
    XXH3_128bits_reset(state.get());
    buffer.resize(size_t(1) << 20);
    for (uint64_t left = size; left > 0;) {
        const ssize_t n = ::read(fd, buffer.data(), std::min<uint64_t>(left, buffer.size()));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return std::nullopt;
        XXH3_128bits_update(state.get(), buffer.data(), static_cast<size_t>(n));
        left -= static_cast<uint64_t>(n);
    }
    const XXH128_hash_t h = XXH3_128bits_digest(state.get());
    return digest_text(h.high64, h.low64);
}

// Whether `name` in the directory `dir` is a regular file (not a link, FIFO or device: never
// followed, never waited on) of exactly `size` bytes with `digest`. One open and one fstat, a size
// that differs costs no read, and the bytes go through the caller's reused buffer: no allocation
// per file.
bool holds_file(int dir, const char* name, uint64_t size, const std::string& digest,
                std::vector<char>& buffer) {
    const int fd = ::openat(dir, name, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return false;
    struct stat st {};
    bool same =
        ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && static_cast<uint64_t>(st.st_size) == size;
    same = same && digest_of(fd, size, buffer) == digest;
    ::close(fd);
    return same;
}

// The directory `sub` ("" or "a/b/") of `out`, every component opened without following a
// link (out itself too): a directory swapped for a link anywhere on the path fails to open.
int open_beneath(const fs::path& out, std::string_view sub) {
    constexpr int kFlags = O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC;
    int fd = ::open(out.c_str(), kFlags);
    while (fd >= 0 && !sub.empty()) {
        const size_t slash = sub.find('/');
        const std::string name(sub.substr(0, slash));
        const int next = ::openat(fd, name.c_str(), kFlags);
        ::close(fd);
        fd = next;
        sub = slash == std::string_view::npos ? std::string_view() : sub.substr(slash + 1);
    }
    return fd;
}

} // namespace

std::optional<std::string> build_inputs_hash(const std::string& material_path,
                                             const std::vector<std::string>& scene_paths,
                                             const std::string& options) {
    std::vector<std::string> parts{"material"};
    if (!material_path.empty()) {
        auto bytes = read_whole(material_path, kMaxInputBytes);
        if (!bytes) return std::nullopt;
        parts.push_back(std::move(*bytes));
    }
    for (const std::string& path : scene_paths) {
        auto bytes = read_whole(path, kMaxInputBytes);
        if (!bytes) return std::nullopt;
        parts.push_back("scene " + fs::path(path).filename().string());
        parts.push_back(std::move(*bytes));
    }
    parts.push_back("options " + options);
    return content_hash(parts);
}

const std::string& executable_digest() {
    static const std::string digest = [] {
        // Unreadable: a digest no record matches, so every build runs.
        const int fd = ::open("/proc/self/exe", O_RDONLY | O_CLOEXEC);
        struct stat st {};
        std::vector<char> buffer;
        std::optional<std::string> d;
        if (fd >= 0 && ::fstat(fd, &st) == 0)
            d = digest_of(fd, static_cast<uint64_t>(st.st_size), buffer);
        if (fd >= 0) ::close(fd);
        return d ? *d : std::string("unreadable executable");
    }();
    return digest;
}

std::string record_key(const std::string& inputs_hash, const std::string& shard) {
    return content_hash({inputs_hash, shard, executable_digest()}); // with the toolchain's
}

fs::path record_file(const BuildCache& cache, const fs::path& out) {
    return cache.dir() / "records" / (content_hash({normal_output_path(out).string()}) + ".record");
}

BuildRecord make_record(const std::string& key, size_t variants, size_t shaders,
                        const FileMap& files) {
    BuildRecord r{key, variants, shaders, {}};
    for (const auto& [path, bytes] : files)
        r.files.push_back({path, bytes.size(), file_digest(bytes)});
    return r;
}

namespace {

// The record in `file` read by `use` (a RecordReader over it); false if it cannot be opened.
bool with_record(const fs::path& file, const std::function<void(RecordReader&)>& use) {
    SafeRead seen;
    std::FILE* in = open_regular_stream(file, seen);
    if (!in) return false;
    RecordReader reader(in);
    use(reader);
    std::fclose(in);
    return true;
}

} // namespace

std::optional<BuildRecord> read_record(const fs::path& file) {
    std::optional<BuildRecord> r;
    with_record(file, [&](RecordReader& reader) {
        BuildRecord all{reader.head().key, reader.head().variants, reader.head().shaders, {}};
        for (RecordedFile f; reader.next(f);)
            all.files.push_back(std::move(f));
        if (reader.ok()) r = std::move(all);
    });
    return r;
}

std::optional<RecordHead> read_record_head(const fs::path& file) {
    std::optional<RecordHead> r;
    with_record(file, [&](RecordReader& reader) {
        if (reader.ok()) r = reader.head();
    });
    return r;
}

std::optional<std::vector<std::string>> record_top_entries(const fs::path& file) {
    std::optional<std::vector<std::string>> tops;
    with_record(file, [&](RecordReader& reader) {
        std::set<std::string> seen;
        for (RecordedFile f; reader.next(f);)
            seen.insert(f.path.substr(0, f.path.find('/')));
        if (reader.ok()) tops.emplace(seen.begin(), seen.end());
    });
    return tops;
}

std::optional<std::string> store_record(const fs::path& file, const BuildRecord& record) {
    return store_record(file, record.key, record.variants, record.shaders, record.files.size(),
                        [&](const std::function<void(const RecordedFile&)>& each) {
                            for (const RecordedFile& f : record.files)
                                each(f);
                        });
}

std::optional<std::string> store_record(const fs::path& file, const std::string& key,
                                        size_t variants, size_t shaders, size_t count,
                                        const ListFiles& files) {
    std::error_code ec;
    fs::create_directories(file.parent_path(), ec);
    if (ec) return "cannot create " + file.parent_path().string() + ": " + ec.message();
    return write_file_atomically(file, [&](const std::function<void(std::string_view)>& write) {
        write(record_head(key, variants, shaders, count));
        files([&](const RecordedFile& f) { write(record_line(f)); });
    });
}

std::string record_not_stored(const std::string& why) {
    return "the build record was not stored (" + why +
           "): the output is whole, but the next build of these inputs runs again instead of "
           "finding it up to date";
}

namespace {

// Whether each of `files` (sorted by path) is in `out` as recorded.
bool files_intact(const fs::path& out, const std::vector<RecordedFile>& files, unsigned threads) {
    // Files by directory (the sorted paths keep each directory's files together): each
    // directory opened once, its files opened relative to it, so no path is walked twice.
    std::vector<std::pair<size_t, size_t>> dirs; // [begin, end) in files
    auto parent = [&](size_t i) {
        const std::string& p = files[i].path;
        return std::string_view(p).substr(0, p.rfind('/') + 1);
    };
    for (size_t i = 0; i < files.size(); ++i)
        if (i == 0 || parent(i) != parent(i - 1))
            dirs.push_back({i, i + 1});
        else
            dirs.back().second = i + 1;
    std::atomic<bool> intact{true};
    parallel_for(dirs.size(), threads, [&](size_t d) {
        if (!intact) return;
        const auto [begin, end] = dirs[d];
        const std::string_view sub = parent(begin); // "" or "a/b/"
        const int fd = open_beneath(out, sub);
        thread_local std::vector<char> buffer;
        for (size_t i = begin; fd >= 0 && intact && i < end; ++i) {
            const RecordedFile& f = files[i];
            const char* name = f.path.c_str() + parent(i).size();
            if (!holds_file(fd, name, f.size, f.digest, buffer)) intact = false;
        }
        if (fd < 0)
            intact = false;
        else
            ::close(fd);
    });
    return intact;
}

// Recorded files checked at once.
constexpr size_t kFilesPerSlice = size_t(1) << 16;

} // namespace

bool outputs_intact(const fs::path& out, const BuildRecord& record, unsigned threads) {
    return files_intact(out, record.files, threads);
}

bool outputs_intact(const fs::path& out, const fs::path& file, unsigned threads) {
    bool intact = false;
    const bool opened = with_record(file, [&](RecordReader& reader) {
        std::vector<RecordedFile> slice;
        RecordedFile f;
        bool more = true;
        intact = true;
        while (intact && more) {
            slice.clear();
            while (slice.size() < kFilesPerSlice && (more = reader.next(f)))
                slice.push_back(f);
            intact = files_intact(out, slice, threads);
        }
        intact = intact && reader.ok();
    });
    return opened && intact;
}

bool record_covers_manifest(const fs::path& file, std::FILE* manifest, const fs::path& scratch,
                            const std::vector<std::string>& also, size_t names_per_run) {
    FileRuns runs(scratch);
    std::vector<std::string> held = also;
    held.push_back("manifest.json");
    bool spilled = true;
    auto sort_held = [&] {
        std::sort(held.begin(), held.end());
        held.erase(std::unique(held.begin(), held.end()), held.end());
    };
    const std::string why = manifest_named_files(manifest, [&](std::string&& p) {
        held.push_back(std::move(p));
        if (held.size() < names_per_run) return;
        sort_held();
        FileRuns::Run run = runs.begin_run();
        for (const std::string& name : held)
            run.add(name, 0, {});
        spilled = spilled && !run.finish();
        held.clear();
    });
    if (!why.empty() || !spilled) return false;
    sort_held();
    // Both in path order: one pass over the record finds each name or shows it missing.
    bool all = true, read_back = false;
    const bool opened = with_record(file, [&](RecordReader& reader) {
        RecordedFile f;
        bool have = reader.next(f);
        size_t next = 0;
        read_back = runs.merged(
            [&](RunRecord& r) {
                if (next == held.size()) return false;
                r.path = held[next++];
                return true;
            },
            [&](const RunRecord& name) {
                while (all && have && f.path < name.path)
                    have = reader.next(f);
                all = all && have && f.path == name.path;
            });
    });
    return opened && read_back && all;
}

} // namespace watergen
