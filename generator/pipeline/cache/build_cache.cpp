#include "watergen/pipeline/cache/build_cache.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <set>
#include <thread>
#include <unistd.h>

#include <glslang/build_info.h>
#include <spirv-tools/libspirv.h>
#include <spirv_cross/spirv_cross_c.h>
#include <xxhash.h>

#include "watergen/pipeline/output/output_writer.h"
#include "watergen/pipeline/output/safe_read.h"

namespace watergen {

namespace fs = std::filesystem;

namespace {

// Version 2: "watergen-cache 2\n<key>\n", then the records, each with its size and XXH3-128
// hash. The key line ties an entry to its name: an entry copied under another key is damage.
constexpr const char* kMagic = "watergen-cache 2\n";
constexpr const char* kPreviousMagic = "watergen-cache 1\n";

std::string hex16(uint64_t h) {
    char s[17];
    std::snprintf(s, sizeof s, "%016llx", static_cast<unsigned long long>(h));
    return s;
}

// Names taken from a damaged entry go into messages: no control characters, bounded length.
std::string printable(const std::string& name) {
    std::string s = name.substr(0, 120);
    for (char& c : s)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return s.size() < name.size() ? s + "..." : s;
}

bool next_line(const std::string& data, size_t& pos, std::string& line) {
    const size_t nl = data.find('\n', pos);
    if (nl == std::string::npos) return false;
    line = data.substr(pos, nl - pos);
    pos = nl + 1;
    return true;
}

// "<digits>" no larger than `limit`.
std::optional<size_t> parse_size(const std::string& text, size_t limit) {
    if (text.empty() || text.size() > 12 ||
        text.find_first_not_of("0123456789") != std::string::npos)
        return std::nullopt;
    const unsigned long long n = std::stoull(text);
    if (n > limit) return std::nullopt;
    return static_cast<size_t>(n);
}

// The files of the entry for `key` if it is exactly `expected`, every record named plainly and
// of the recorded size and hash; otherwise nullopt and the first problem in `why`.
std::optional<FileMap> verify_entry(const std::string& data, const std::string& key,
                                    const std::vector<std::string>& expected, std::string& why) {
    const std::string magic = kMagic;
    if (data.compare(0, magic.size(), magic) != 0) {
        why = "not a version-2 cache entry";
        return std::nullopt;
    }
    size_t pos = magic.size();
    std::string written_for;
    if (!next_line(data, pos, written_for) || written_for != key) {
        why = "written for key '" + printable(written_for) + "', not for its own";
        return std::nullopt;
    }
    const std::set<std::string> wanted(expected.begin(), expected.end());
    FileMap files;
    while (pos < data.size()) {
        std::string path, size_text, digest;
        if (!next_line(data, pos, path) || !next_line(data, pos, size_text) ||
            !next_line(data, pos, digest)) {
            why = "truncated record header";
            return std::nullopt;
        }
        const std::string name = "record '" + printable(path) + "'";
        if (!is_plain_relative_path(path))
            why = name + " is not a plain relative path";
        else if (!wanted.count(path))
            why = "unexpected " + name;
        else if (files.count(path))
            why = name + " appears twice";
        const std::optional<size_t> size = parse_size(size_text, data.size() - pos);
        if (why.empty() && !size)
            why = name + ": size '" + printable(size_text) + "' is not a number within the entry";
        if (!why.empty()) return std::nullopt;
        std::string bytes = data.substr(pos, *size);
        pos += *size;
        if (file_digest(bytes) != digest) {
            why = name + ": content does not match its hash";
            return std::nullopt;
        }
        files.emplace(path, std::move(bytes));
    }
    for (const std::string& path : wanted)
        if (!files.count(path)) {
            why = "missing record '" + path + "'";
            return std::nullopt;
        }
    return files;
}

} // namespace

const std::string& toolchain_fingerprint() {
    // "files 2": an entry holds no SPIRV-Cross text of the HLSL path (entries of files 1 did).
    // "files 3": variant.json lists the geometry axis among its choices (and a mesh's stages).
    static const std::string text =
        std::string("watergen ") + WATERGEN_VERSION + "; files 3; glslang " +
        std::to_string(GLSLANG_VERSION_MAJOR) + "." + std::to_string(GLSLANG_VERSION_MINOR) + "." +
        std::to_string(GLSLANG_VERSION_PATCH) + "; SPIRV-Tools " + spvSoftwareVersionString() +
        "; SPIRV-Cross C API " + std::to_string(SPVC_C_API_VERSION_MAJOR) + "." +
        std::to_string(SPVC_C_API_VERSION_MINOR) + "." + std::to_string(SPVC_C_API_VERSION_PATCH);
    return text;
}

std::string content_hash(const std::vector<std::string>& parts) {
    XXH64_state_t* state = XXH64_createState();
    XXH64_reset(state, 0);
    auto feed = [&](const std::string& s) {
        const uint64_t n = s.size();
        XXH64_update(state, &n, sizeof n);
        XXH64_update(state, s.data(), s.size());
    };
    feed(toolchain_fingerprint());
    for (const auto& p : parts)
        feed(p);
    const uint64_t h = XXH64_digest(state);
    XXH64_freeState(state);
    return hex16(h);
}

std::string file_digest(std::string_view bytes) {
    const XXH128_hash_t h = XXH3_128bits(bytes.data(), bytes.size());
    return digest_text(h.high64, h.low64);
}

std::string digest_text(uint64_t high, uint64_t low) {
    return hex16(high) + hex16(low);
}

std::string cache_record(const std::string& path, const std::string& bytes) {
    return path + "\n" + std::to_string(bytes.size()) + "\n" + file_digest(bytes) + "\n" + bytes;
}

fs::path BuildCache::entry(const std::string& hash) const {
    return dir_ / hash.substr(0, 2) / (hash + ".wgc");
}

CacheLookup BuildCache::load(const std::string& hash,
                             const std::vector<std::string>& expected) const {
    CacheLookup lookup;
    if (!enabled()) return lookup;
    const fs::path path = entry(hash);
    const SafeRead read = read_regular_file(path, kMaxCacheEntryBytes);
    // An entry of the previous format is outdated, not damaged: a quiet miss, overwritten by the
    // store.
    if (read.missing || (read.bytes && read.bytes->rfind(kPreviousMagic, 0) == 0)) return lookup;
    // No directory to hold the entry (a cache path under a regular file): nothing was ever
    // stored, a miss; the store says once that the cache cannot be written.
    std::error_code ec;
    if (!read.bytes && !fs::is_directory(path.parent_path(), ec)) return lookup;
    if (read.bytes)
        lookup.files = verify_entry(*read.bytes, hash, expected, lookup.rejected);
    else
        lookup.rejected = read.why;
    if (!lookup.rejected.empty()) remove_if_same(path, read);
    return lookup;
}

std::optional<std::string> BuildCache::store(const std::string& hash, const FileMap& files) const {
    if (!enabled()) return std::nullopt;
    std::string data = kMagic + hash + "\n";
    for (const auto& [path, bytes] : files)
        data += cache_record(path, bytes);
    const fs::path target = entry(hash);
    std::error_code ec;
    fs::create_directories(target.parent_path(), ec);
    if (ec) return "cannot create " + target.parent_path().string() + ": " + ec.message();
    // Unique per process and thread: two jobs may store the same entry at once.
    static std::atomic<unsigned> counter{0};
    const fs::path tmp = target.string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                         std::to_string(std::hash<std::thread::id>{}(std::this_thread::get_id())) +
                         "-" + std::to_string(counter++);
    if (auto e = write_new_file(tmp, data)) {
        fs::remove(tmp, ec);
        return e;
    }
    // rename() replaces whatever is at the entry's name (a link itself, never its target).
    fs::rename(tmp, target, ec);
    if (ec) {
        const std::string why = ec.message();
        fs::remove(tmp, ec);
        return "cannot rename into " + target.string() + ": " + why;
    }
    return std::nullopt;
}

fs::path default_cache_dir() {
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
        return fs::path(xdg) / "watergen";
    if (const char* home = std::getenv("HOME"); home && *home)
        return fs::path(home) / ".cache" / "watergen";
    return {};
}

CacheUse BuildCache::load_or_make(const std::string& hash, const std::vector<std::string>& expected,
                                  const std::function<std::optional<FileMap>()>& make) const {
    CacheLookup lookup = load(hash, expected);
    CacheUse use{std::move(lookup.files), false, std::move(lookup.rejected)};
    use.cached = use.files.has_value();
    if (use.cached) return use;
    use.files = make();
    // A cache that cannot be written only costs time: said once, and the build goes on.
    if (use.files)
        if (auto failure = store(hash, *use.files)) warn_unwritable(*failure);
    return use;
}

void BuildCache::warn_unwritable(const std::string& why) const {
    if (!unwritable_) return;
    std::call_once(*unwritable_, [&] {
        std::fprintf(stderr,
                     "watergen: warning: cache %s cannot be written (%s); building without "
                     "storing\n",
                     dir_.string().c_str(), why.c_str());
    });
}

Diagnostic BuildCache::rejected_warning(const std::string& hash, const std::string& why) const {
    return {Severity::Warning,
            entry(hash).string(),
            0,
            0,
            "",
            "cache entry failed verification (" + why + "); evicted and rebuilt"};
}

} // namespace watergen
