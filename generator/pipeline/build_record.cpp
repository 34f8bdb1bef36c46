#include "watergen/pipeline/build_record.h"

#include <atomic>
#include <fstream>
#include <sstream>

#include <xxhash.h>

#include "watergen/pipeline/output_target.h"
#include "watergen/pipeline/output_writer.h"
#include "watergen/pipeline/parallel_build.h"
#include "watergen/pipeline/safe_read.h"

namespace watergen {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMagic = "watergen-record 1";

// Description files are at most 4 MiB (json_source.h); a record file far below this.
constexpr size_t kMaxInputBytes = size_t(8) << 20;
constexpr size_t kMaxRecordBytes = size_t(512) << 20;

std::optional<std::string> read_whole(const fs::path& path, size_t limit) {
    const SafeRead r = read_regular_file(path, limit);
    return r.bytes;
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
        std::ifstream in("/proc/self/exe", std::ios::binary);
        std::stringstream ss;
        ss << in.rdbuf();
        // Unreadable: a digest no record matches, so every build runs.
        return in ? file_digest(ss.str()) : std::string("unreadable executable");
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

std::string record_text(const BuildRecord& r) {
    std::ostringstream s;
    s << kMagic << "\nkey " << r.key << "\nvariants " << r.variants << "\nshaders " << r.shaders
      << "\nfiles " << r.files.size() << "\n";
    for (const RecordedFile& f : r.files)
        s << f.size << ' ' << f.digest << ' ' << f.path << '\n';
    return s.str();
}

std::optional<BuildRecord> parse_record(const std::string& text) {
    std::istringstream in(text);
    std::string line, word;
    BuildRecord r;
    size_t count = 0;
    if (!std::getline(in, line) || line != kMagic) return std::nullopt;
    if (!(in >> word >> r.key) || word != "key") return std::nullopt;
    if (!(in >> word >> r.variants) || word != "variants") return std::nullopt;
    if (!(in >> word >> r.shaders) || word != "shaders") return std::nullopt;
    if (!(in >> word >> count) || word != "files" || in.get() != '\n') return std::nullopt;
    for (size_t i = 0; i < count; ++i) {
        RecordedFile f;
        if (!(in >> f.size >> f.digest) || in.get() != ' ' || !std::getline(in, f.path) ||
            !is_plain_relative_path(f.path))
            return std::nullopt;
        r.files.push_back(std::move(f));
    }
    if (in.peek() != std::char_traits<char>::eof()) return std::nullopt;
    return r;
}

std::optional<BuildRecord> read_record(const fs::path& file) {
    auto text = read_whole(file, kMaxRecordBytes);
    return text ? parse_record(*text) : std::nullopt;
}

void store_record(const fs::path& file, const BuildRecord& record) {
    std::error_code ec;
    fs::create_directories(file.parent_path(), ec);
    if (!ec) write_file_atomically(file, record_text(record));
}

bool outputs_intact(const fs::path& out, const BuildRecord& record, unsigned threads) {
    std::atomic<bool> intact{true};
    parallel_for(record.files.size(), threads, [&](size_t i) {
        if (!intact) return;
        const RecordedFile& f = record.files[i];
        // read_regular_file checks the size before it reads: a changed size costs no read.
        const SafeRead r = read_regular_file(out / f.path, f.size);
        if (!r.bytes || r.bytes->size() != f.size || file_digest(*r.bytes) != f.digest)
            intact = false;
    });
    return intact;
}

} // namespace watergen
