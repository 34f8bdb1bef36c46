// The build record as text, and what it vouches for: kept apart from the filesystem work of
// build_record.cpp so that the record fuzzer (tests/fuzz/record_fuzzer.cpp) builds it alone.
#include <algorithm>
#include <functional>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "watergen/pipeline/build_record.h"
#include "watergen/pipeline/manifest_files.h"
#include "watergen/pipeline/output_writer.h"

namespace watergen {

namespace {

constexpr const char* kMagic = "watergen-record 1";

} // namespace

std::string record_head(const std::string& key, size_t variants, size_t shaders, size_t files) {
    return fmt::format("{}\nkey {}\nvariants {}\nshaders {}\nfiles {}\n", kMagic, key, variants,
                       shaders, files);
}

std::string record_line(const RecordedFile& f) {
    return fmt::format("{} {} {}\n", f.size, f.digest, f.path);
}

std::string record_text(const BuildRecord& r) {
    std::string text = record_head(r.key, r.variants, r.shaders, r.files.size());
    for (const RecordedFile& f : r.files)
        text += record_line(f);
    return text;
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

namespace {

// Whether every path `read_names` hands over is recorded (and manifest.json is).
bool covers(
    const BuildRecord& record,
    const std::function<std::string(const std::function<void(std::string&&)>&)>& read_names) {
    std::vector<std::string_view> recorded;
    recorded.reserve(record.files.size());
    for (const RecordedFile& f : record.files)
        recorded.push_back(f.path);
    std::sort(recorded.begin(), recorded.end());
    auto has = [&](std::string_view p) {
        return std::binary_search(recorded.begin(), recorded.end(), p);
    };
    bool all = has("manifest.json");
    const std::string why = read_names([&](std::string&& p) { all = all && has(p); });
    return why.empty() && all;
}

} // namespace

bool record_covers_manifest(const BuildRecord& record, const std::string& manifest) {
    return covers(record, [&](const std::function<void(std::string &&)>& each) {
        std::vector<std::string> named;
        std::string why = manifest_named_files(manifest, named);
        for (std::string& p : named)
            each(std::move(p));
        return why;
    });
}

bool record_covers_manifest(const BuildRecord& record, std::FILE* manifest) {
    return covers(record, [&](const std::function<void(std::string &&)>& each) {
        return manifest_named_files(manifest, each);
    });
}

} // namespace watergen
