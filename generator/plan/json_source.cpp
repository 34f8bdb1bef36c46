#include "watergen/plan/json_source.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <string_view>
#include <unordered_set>
#include <vector>

#include <fmt/format.h>

namespace watergen {

namespace {

// nlohmann's SAX events carry no position, but its lexer pulls characters one at a time
// through the iterator it is given: counting them tells each event where the lexer stands.
struct CountingIterator {
    using iterator_category = std::input_iterator_tag;
    using value_type = char;
    using difference_type = std::ptrdiff_t;
    using pointer = const char*;
    using reference = const char&;

    const char* p = nullptr;
    const char* base = nullptr;
    size_t* consumed = nullptr;

    reference operator*() const { return *p; }
    CountingIterator& operator++() {
        ++p;
        *consumed = static_cast<size_t>(p - base);
        return *this;
    }
    CountingIterator operator++(int) {
        CountingIterator old = *this;
        ++*this;
        return old;
    }
    bool operator==(const CountingIterator& o) const { return p == o.p; }
    bool operator!=(const CountingIterator& o) const { return p != o.p; }
};

bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}
bool is_scalar_char(char c) {
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '.' ||
           c == '+' || c == '-';
}

std::string escape_pointer_token(const std::string& key) {
    std::string s;
    for (char c : key) {
        if (c == '~')
            s += "~0";
        else if (c == '/')
            s += "~1";
        else
            s += c;
    }
    return s;
}

} // namespace

LineIndex::LineIndex(std::string_view text) : starts_{0}, size_(text.size()) {
    for (size_t i = text.find('\n'); i != std::string_view::npos; i = text.find('\n', i + 1))
        starts_.push_back(i + 1);
}

JsonPosition LineIndex::at(size_t offset) const {
    offset = std::min(offset, size_);
    // The last line starting at or before the offset.
    const auto line = std::upper_bound(starts_.begin(), starts_.end(), offset) - 1;
    return JsonPosition{static_cast<int>(line - starts_.begin()) + 1,
                        static_cast<int>(offset - *line) + 1};
}

JsonPosition position_of_offset(const std::string& text, size_t offset) {
    return LineIndex(text).at(offset);
}

std::string json_child(const std::string& parent, const std::string& key) {
    return parent + "/" + escape_pointer_token(key);
}
std::string json_child(const std::string& parent, size_t index) {
    return parent + "/" + std::to_string(index);
}

std::string json_describe(const Json& v) {
    switch (v.type()) {
    case Json::value_t::null:
        return "null";
    case Json::value_t::boolean:
        return std::string("a boolean (") + (v.get<bool>() ? "true" : "false") + ")";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float:
        return "a number (" + v.dump() + ")";
    case Json::value_t::string:
        return "a string (" + v.dump() + ")";
    case Json::value_t::array:
        return "an array";
    case Json::value_t::object:
        return "an object";
    default:
        return "a " + std::string(v.type_name());
    }
}

// Builds the DOM and records, per JSON pointer, where its key (object members) or its value
// (array elements, the root) starts.
class JsonSaxBuilder {
  public:
    JsonSaxBuilder(JsonSource& out, const std::string& text, const size_t& consumed)
        : out_(out), text_(text), lines_(text), consumed_(consumed) {}

    bool null() { return value(Json(nullptr), false); }
    bool boolean(bool b) { return value(Json(b), false); }
    bool number_integer(Json::number_integer_t v) { return value(Json(v), false); }
    bool number_unsigned(Json::number_unsigned_t v) { return value(Json(v), false); }
    bool number_float(Json::number_float_t v, const std::string&) { return value(Json(v), false); }
    bool string(std::string& s) { return value(Json(s), true); }
    bool binary(Json::binary_t&) { return fail("binary values are not JSON text"); }
    bool start_object(std::size_t) { return !too_deep() && value(Json::object(), false, true); }
    bool end_object() {
        stack_.pop_back();
        return true;
    }
    bool start_array(std::size_t) { return !too_deep() && value(Json::array(), false, true); }
    bool end_array() {
        stack_.pop_back();
        return true;
    }
    bool key(std::string& k) {
        Frame& f = stack_.back();
        // Json's objects keep their keys in order, and finding one is a walk through them:
        // the frame's own set says whether a key came before (a walk per key made a file of
        // many keys quadratic).
        if (!f.keys.insert(k).second) {
            const JsonPosition p = token_start(true);
            error_ = Diagnostic{Severity::Error,
                                out_.file_,
                                p.line,
                                p.column,
                                "",
                                json_child(f.pointer, k) + ": duplicate key '" + k + "'"};
            return false;
        }
        f.key = k;
        out_.positions_[json_child(f.pointer, k)] = token_start(true);
        return true;
    }
    bool parse_error(std::size_t position, const std::string&,
                     const nlohmann::detail::exception& ex) {
        // nlohmann's message: "[json.exception.parse_error.101] parse error at line L, column C:
        // what".
        std::string what = ex.what();
        if (const size_t colon = what.find(": "); colon != std::string::npos)
            what = what.substr(colon + 2);
        const size_t offset = position > 0 ? position - 1 : 0;
        const JsonPosition p = lines_.at(offset);
        error_ =
            Diagnostic{Severity::Error, out_.file_, p.line, p.column, "", "invalid JSON: " + what};
        return false;
    }

    const std::optional<Diagnostic>& error() const { return error_; }

  private:
    struct Frame {
        Json* node;
        std::string pointer;
        std::string key;
        std::unordered_set<std::string> keys = {}; // an object's, so far
    };

    // Stops at the first container past the limit, before anything below it is stored.
    bool too_deep() {
        if (stack_.size() < kMaxJsonDepth) return false;
        const JsonPosition p = token_start(false, true);
        error_ = Diagnostic{
            Severity::Error,
            out_.file_,
            p.line,
            p.column,
            "",
            fmt::format(
                "invalid JSON: nested deeper than {} levels, the limit for description files",
                kMaxJsonDepth)};
        return true;
    }

    bool fail(const std::string& what) {
        const JsonPosition p = lines_.at(consumed_);
        error_ = Diagnostic{Severity::Error, out_.file_, p.line, p.column, "", what};
        return false;
    }

    // Start of the token the lexer has just read (a string when `quoted`; containers have
    // consumed only their opening bracket).
    JsonPosition token_start(bool quoted, bool container = false) const {
        size_t i = consumed_;
        if (container) return lines_.at(i > 0 ? i - 1 : 0);
        while (i > 0 && is_space(text_[i - 1]))
            --i;
        if (quoted) {
            // text_[i - 1] is the closing quote; find the opening one (not escaped).
            size_t j = i >= 2 ? i - 2 : 0;
            while (j > 0) {
                if (text_[j] == '"') {
                    size_t slashes = 0;
                    while (j >= slashes + 1 && text_[j - slashes - 1] == '\\')
                        ++slashes;
                    if (slashes % 2 == 0) break;
                }
                --j;
            }
            return lines_.at(j);
        }
        // Numbers are read one character past their end: step back over that look-ahead.
        if (i > 0 && !is_scalar_char(text_[i - 1])) {
            --i;
            while (i > 0 && is_space(text_[i - 1]))
                --i;
        }
        while (i > 0 && is_scalar_char(text_[i - 1]))
            --i;
        return lines_.at(i);
    }

    bool value(Json v, bool quoted, bool container = false) {
        Json* slot = nullptr;
        std::string pointer;
        if (stack_.empty()) {
            out_.root_ = std::move(v);
            slot = &out_.root_;
            out_.positions_[""] = token_start(quoted, container);
        } else {
            Frame& f = stack_.back();
            if (f.node->is_array()) {
                pointer = json_child(f.pointer, f.node->size());
                f.node->push_back(std::move(v));
                slot = &f.node->back();
                out_.positions_[pointer] = token_start(quoted, container);
            } else {
                pointer = json_child(f.pointer, f.key);
                // Appended without the ordered map's search (key() saw it is new); a child's
                // slot is used only while the parent gains nothing, so it stays valid.
                auto& members = f.node->get_ref<Json::object_t&>();
                members.Container::emplace_back(f.key, std::move(v));
                slot = &members.back().second;
                // Members are located at their key (recorded in key()).
            }
        }
        if (container) stack_.push_back(Frame{slot, pointer, ""});
        return true;
    }

    JsonSource& out_;
    const std::string& text_;
    const LineIndex lines_;
    const size_t& consumed_;
    std::vector<Frame> stack_;
    std::optional<Diagnostic> error_;
};

namespace {

constexpr std::string_view kUtf8ByteOrderMark = "\xEF\xBB\xBF";

Diagnostic too_large(const std::string& text, const std::string& file) {
    const JsonPosition p = position_of_offset(text, kMaxJsonBytes);
    return Diagnostic{
        Severity::Error,
        file,
        p.line,
        p.column,
        "",
        fmt::format("the file is larger than {} bytes (4 MiB), the limit for description files",
                    kMaxJsonBytes)};
}

} // namespace

std::optional<JsonSource> JsonSource::parse(const std::string& input, const std::string& file,
                                            Diagnostic* error) {
    const bool bom =
        std::string_view(input).substr(0, kUtf8ByteOrderMark.size()) == kUtf8ByteOrderMark;
    const std::string text = bom ? input.substr(kUtf8ByteOrderMark.size()) : input;
    if (text.size() > kMaxJsonBytes) {
        if (error) *error = too_large(text, file);
        return std::nullopt;
    }
    JsonSource src;
    src.file_ = file;
    size_t consumed = 0;
    JsonSaxBuilder sax(src, text, consumed);
    CountingIterator first{text.data(), text.data(), &consumed};
    CountingIterator last{text.data() + text.size(), text.data(), &consumed};
    const bool ok = Json::sax_parse(first, last, &sax);
    if (!ok || sax.error()) {
        if (error)
            *error = sax.error() ? *sax.error()
                                 : Diagnostic{Severity::Error, file, 0, 0, "", "invalid JSON"};
        return std::nullopt;
    }
    src.index();
    return src;
}

std::optional<JsonSource> JsonSource::load(const std::filesystem::path& path, Diagnostic* error) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
        if (error)
            *error = Diagnostic{
                Severity::Error, path.string(), 0, 0, "", "is a directory; expected a JSON file"};
        return std::nullopt;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        if (error)
            *error = Diagnostic{Severity::Error, path.string(), 0, 0, "", "cannot open the file"};
        return std::nullopt;
    }
    // One byte past the limit (and the byte order mark) is enough to tell that a file is too large.
    const size_t enough = kMaxJsonBytes + kUtf8ByteOrderMark.size() + 1;
    std::string text;
    char chunk[1 << 16];
    while (text.size() < enough && in.read(chunk, sizeof chunk).gcount() > 0)
        text.append(chunk, static_cast<size_t>(in.gcount()));
    if (text.size() > enough) text.resize(enough);
    return parse(text, path.string(), error);
}

JsonSource::JsonSource(const JsonSource& other)
    : file_(other.file_), root_(other.root_), positions_(other.positions_) {
    index();
}

JsonSource& JsonSource::operator=(const JsonSource& other) {
    if (this != &other) {
        file_ = other.file_;
        root_ = other.root_;
        positions_ = other.positions_;
        index();
    }
    return *this;
}

void JsonSource::index() {
    values_.clear();
    values_.reserve(positions_.size());
    // Depth is bounded (kMaxJsonDepth): a stack of the containers still to visit.
    std::vector<std::pair<std::string, const Json*>> todo = {{"", &root_}};
    while (!todo.empty()) {
        auto [pointer, value] = std::move(todo.back());
        todo.pop_back();
        if (value->is_object())
            for (const auto& [key, child] : value->items())
                todo.emplace_back(json_child(pointer, key), &child);
        else if (value->is_array())
            for (size_t i = 0; i < value->size(); ++i)
                todo.emplace_back(json_child(pointer, i), &(*value)[i]);
        if (!pointer.empty()) values_.emplace(std::move(pointer), value);
    }
}

const Json* JsonSource::find(const std::string& pointer) const {
    if (pointer.empty()) return &root_;
    const auto it = values_.find(pointer);
    return it == values_.end() ? nullptr : it->second;
}

JsonPosition JsonSource::position(const std::string& pointer) const {
    // A pointer below a leaf (e.g. a component of a number that should have been an array)
    // falls back to the nearest recorded ancestor.
    std::string p = pointer;
    for (;;) {
        if (auto it = positions_.find(p); it != positions_.end()) return it->second;
        const size_t slash = p.rfind('/');
        if (slash == std::string::npos) return {};
        p = p.substr(0, slash);
    }
}

std::string JsonSource::where(const std::string& pointer) const {
    const JsonPosition p = position(pointer);
    return file_ + ":" + std::to_string(p.line) + ":" + std::to_string(p.column);
}

Diagnostic JsonSource::error(const std::string& pointer, const std::string& what) const {
    const JsonPosition p = position(pointer);
    return Diagnostic{Severity::Error, file_, p.line,
                      p.column,        "",    (pointer.empty() ? "/" : pointer) + ": " + what};
}

} // namespace watergen
