// The build record as text, and what it vouches for: kept apart from the filesystem work of
// build_record.cpp so that the record fuzzer (tests/fuzz/record_fuzzer.cpp) builds it alone.
#include <algorithm>
#include <sstream>
#include <string_view>

#include "watergen/pipeline/build_record.h"
#include "watergen/pipeline/manifest_files.h"
#include "watergen/pipeline/output_writer.h"

namespace watergen {

namespace {

constexpr const char* kMagic = "watergen-record 1";

} // namespace

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

bool record_covers_manifest(const BuildRecord& record, const std::string& manifest) {
    std::vector<std::string> named{"manifest.json"};
    if (!manifest_named_files(manifest, named).empty()) return false;
    std::vector<std::string_view> recorded;
    recorded.reserve(record.files.size());
    for (const RecordedFile& f : record.files)
        recorded.push_back(f.path);
    std::sort(recorded.begin(), recorded.end());
    return std::all_of(named.begin(), named.end(), [&](const std::string& p) {
        return std::binary_search(recorded.begin(), recorded.end(), std::string_view(p));
    });
}

} // namespace watergen
