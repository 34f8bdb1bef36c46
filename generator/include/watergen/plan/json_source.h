// A JSON description file with the position of every value, so that errors found after
// parsing (an unknown axis, a range the wrong way round) still name file:line:column and the
// JSON path (RFC 6901 pointer, e.g. /axes/fresnel/2) of the offending value.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <nlohmann/json.hpp>

#include "watergen/ir/core/diagnostic.h"

namespace watergen {

using Json =
    nlohmann::ordered_json; // keeps file order, so the first error is the first in the file

struct JsonPosition {
    int line = 0, column = 0; // 1-based; 0 when unknown
};

// Limits of a description file, checked while reading: materials and scenes nest 5 containers
// deep and weigh a few KiB, and without a bound a 120 KB file of 60k nested brackets takes
// quadratic memory (a JSON pointer per level) until allocation fails.
constexpr size_t kMaxJsonDepth = 64;              // nested objects and arrays
constexpr size_t kMaxJsonBytes = size_t(4) << 20; // 4 MiB

class JsonSource {
  public:
    // Parses `text` (named `file` in diagnostics). Syntax errors, duplicate keys, empty input
    // and text beyond the limits above yield nullopt with one Error diagnostic carrying the
    // line and column. A leading UTF-8 byte order mark is skipped; lines and columns count
    // from after it, as if it were not there.
    static std::optional<JsonSource> parse(const std::string& text, const std::string& file,
                                           Diagnostic* error);
    // Reads and parses a file; a missing or unreadable file is an error naming the path. Reads
    // no more than kMaxJsonBytes + 1 bytes, whatever the file's size.
    static std::optional<JsonSource> load(const std::filesystem::path& path, Diagnostic* error);

    JsonSource() = default;
    JsonSource(JsonSource&&) = default;
    JsonSource& operator=(JsonSource&&) = default;
    JsonSource(const JsonSource& other);
    JsonSource& operator=(const JsonSource& other);

    const Json& root() const { return root_; }
    const std::string& file() const { return file_; }
    // The value at `pointer`, found in an index made once: Json's objects keep their keys in
    // order and find one by walking them, so a lookup per member of a large object through
    // the DOM was quadratic. nullptr when there is none.
    const Json* find(const std::string& pointer) const;

    // Where the value at `pointer` starts (its key, for object members).
    JsonPosition position(const std::string& pointer) const;
    // "file:line:column" of the value at `pointer`.
    std::string where(const std::string& pointer) const;
    // Error at the value: message reads "<pointer>: <what>".
    Diagnostic error(const std::string& pointer, const std::string& what) const;

  private:
    std::string file_;
    Json root_;
    std::map<std::string, JsonPosition> positions_;
    std::unordered_map<std::string, const Json*> values_; // every value below the root
    void index();                                         // values_ from root_
    friend class JsonSaxBuilder;
};

// JSON pointer of a member / element below `parent` (escapes ~ and /).
std::string json_child(const std::string& parent, const std::string& key);
std::string json_child(const std::string& parent, size_t index);
// "a number", "a string (\"abc\")", ...: what a value is, for "expected X, got Y".
std::string json_describe(const Json& value);

// The lines of a text, to give the line and column of many offsets: each in O(log lines), the
// index made once in O(size). (Counting from the start for every token made a reader quadratic.)
class LineIndex {
  public:
    explicit LineIndex(std::string_view text);
    // Line and column (1-based, bytes) of byte `offset`; an offset past the end is the end.
    JsonPosition at(size_t offset) const;

  private:
    std::vector<size_t> starts_; // each line's first byte
    size_t size_;
};

// Line and column (1-based) of byte `offset` in `text` (one offset: LineIndex for many).
JsonPosition position_of_offset(const std::string& text, size_t offset);

} // namespace watergen
