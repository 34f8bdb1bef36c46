// The build record as text, and what it vouches for: kept apart from the filesystem work of
// build_record.cpp so that the record fuzzer (tests/fuzz/record_fuzzer.cpp) builds it alone.
#include <algorithm>
#include <cstdio>
#include <functional>
#include <string_view>

#include <fmt/format.h>

#include "watergen/pipeline/manifest/manifest_files.h"
#include "watergen/pipeline/output/output_writer.h"
#include "watergen/pipeline/record/build_record.h"

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

namespace {

// One line of `in` without its '\n'; false at the end of the input or for a line without one.
bool read_line(std::FILE* in, std::string& line) {
    line.clear();
    for (int c; (c = std::getc(in)) != EOF;) {
        if (c == '\n') return true;
        line.push_back(static_cast<char>(c));
    }
    return false;
}

// "<word> <decimal>" (the head's counts) into `value`.
bool read_count(std::FILE* in, const char* word, size_t& value) {
    std::string line;
    const std::string prefix = std::string(word) + " ";
    if (!read_line(in, line) || line.rfind(prefix, 0) != 0) return false;
    const std::string digits = line.substr(prefix.size());
    if (digits.empty() || digits.size() > 18 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
        return false;
    value = std::stoull(digits);
    return true;
}

} // namespace

RecordReader::RecordReader(std::FILE* in) : in_(in) {
    std::string line;
    ok_ = in_ && read_line(in_, line) && line == kMagic && read_line(in_, line) &&
          line.rfind("key ", 0) == 0 && line.size() > 4;
    if (ok_) head_.key = line.substr(4);
    ok_ = ok_ && head_.key.find(' ') == std::string::npos &&
          read_count(in_, "variants", head_.variants) &&
          read_count(in_, "shaders", head_.shaders) && read_count(in_, "files", head_.files);
}

bool RecordReader::next(RecordedFile& f) {
    if (!ok_) return false;
    if (read_ == head_.files) {
        ok_ = std::getc(in_) == EOF; // nothing after the last file
        return false;
    }
    std::string line;
    // "<size> <digest> <path>": the path last, as it may hold spaces.
    const size_t first = read_line(in_, line) ? line.find(' ') : std::string::npos;
    const size_t second = first == std::string::npos ? first : line.find(' ', first + 1);
    if (second == std::string::npos || first == 0 || first > 18 ||
        line.find_first_not_of("0123456789") != first)
        return ok_ = false;
    f.size = std::stoull(line.substr(0, first));
    f.digest = line.substr(first + 1, second - first - 1);
    f.path = line.substr(second + 1);
    // Strictly ascending: a reader matches the paths against others in one pass.
    if (f.digest.empty() || !is_plain_relative_path(f.path) || (read_ > 0 && f.path <= last_))
        return ok_ = false;
    last_ = f.path;
    ++read_;
    return true;
}

std::optional<BuildRecord> parse_record(const std::string& text) {
    if (text.empty()) return std::nullopt;
    std::FILE* in = ::fmemopen(const_cast<char*>(text.data()), text.size(), "r");
    if (!in) return std::nullopt;
    RecordReader reader(in);
    BuildRecord r{reader.head().key, reader.head().variants, reader.head().shaders, {}};
    for (RecordedFile f; reader.next(f);)
        r.files.push_back(std::move(f));
    std::fclose(in);
    if (!reader.ok()) return std::nullopt;
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
