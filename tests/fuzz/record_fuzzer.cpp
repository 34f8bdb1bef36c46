// Build records as a damaged or hostile cache may hold them, with the output's manifest beside
// them: the input is the record text, a NUL byte, then the manifest text. Whatever the bytes, a
// record that parses names only plain relative paths and writes back to a text that parses to
// the same record; a record that covers the manifest holds every file the manifest names.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "watergen/pipeline/manifest/manifest_files.h"
#include "watergen/pipeline/output/output_writer.h"
#include "watergen/pipeline/record/build_record.h"

namespace {

bool same(const watergen::BuildRecord& a, const watergen::BuildRecord& b) {
    if (a.key != b.key || a.variants != b.variants || a.shaders != b.shaders ||
        a.files.size() != b.files.size())
        return false;
    for (size_t i = 0; i < a.files.size(); ++i)
        if (a.files[i].path != b.files[i].path || a.files[i].size != b.files[i].size ||
            a.files[i].digest != b.files[i].digest)
            return false;
    return true;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace watergen;
    const std::string input(reinterpret_cast<const char*>(data), size);
    const size_t nul = input.find('\0');
    const auto record = parse_record(input.substr(0, nul));
    if (!record) return 0;
    for (const RecordedFile& f : record->files)
        if (!is_plain_relative_path(f.path)) std::abort();
    const auto again = parse_record(record_text(*record));
    if (!again || !same(*record, *again)) std::abort();
    const std::string manifest = nul == std::string::npos ? "" : input.substr(nul + 1);
    if (!record_covers_manifest(*record, manifest)) return 0;
    std::vector<std::string> named;
    if (!manifest_named_files(manifest, named).empty()) std::abort();
    for (const std::string& p : named)
        if (std::none_of(record->files.begin(), record->files.end(),
                         [&](const RecordedFile& f) { return f.path == p; }))
            std::abort();
    return 0;
}
