#include "watergen/pipeline/output/json_document.h"

#include <array>
#include <iterator>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace watergen {

// nlohmann's dump(2) breaks lines only between tokens (a string keeps its newlines escaped), so
// an element dumped alone and indented by its depth reads as it would inside the document.
namespace {
constexpr std::string_view kElementIndent = "    "; // an element of a top-level array
} // namespace

JsonDocumentWriter::JsonDocumentWriter(const nlohmann::ordered_json& head, const WriteText& write)
    : write_(write) {
    std::string text = head.dump(2);
    text.resize(text.size() - 2); // the closing "\n}"
    write_(text);
}

void JsonDocumentWriter::begin_array(std::string_view name) {
    write_(",\n  ");
    write_(nlohmann::ordered_json(std::string(name)).dump());
    write_(": [");
    first_ = true;
}

void JsonDocumentWriter::element(const nlohmann::ordered_json& value) {
    const std::string text = value.dump(2);
    std::string out(first_ ? "\n" : ",\n");
    out.reserve(text.size() + text.size() / 8);
    out += kElementIndent;
    for (char c : text) {
        out += c;
        if (c == '\n') out += kElementIndent;
    }
    write_(out);
    first_ = false;
}

void JsonDocumentWriter::end_array() {
    write_(first_ ? "]" : "\n  ]");
}

void JsonDocumentWriter::end() {
    write_("\n}\n");
}

namespace {

using OJson = nlohmann::ordered_json;

// Builds each top-level member (or element of a streamed member) as a DOM of its own and hands
// it over when it is complete.
class PieceBuilder : public nlohmann::json_sax<OJson> {
  public:
    explicit PieceBuilder(const JsonDocumentReader& reader) : reader_(reader) {}
    bool stopped = false;
    std::string error;

    bool null() override { return put(nullptr); }
    bool boolean(bool v) override { return put(v); }
    bool number_integer(number_integer_t v) override { return put(v); }
    bool number_unsigned(number_unsigned_t v) override { return put(v); }
    bool number_float(number_float_t v, const string_t&) override { return put(v); }
    bool string(string_t& v) override { return put(std::move(v)); }
    bool binary(binary_t&) override { return fail("binary value"); }
    bool start_object(std::size_t) override { return open(OJson::object()); }
    bool start_array(std::size_t) override {
        if (stack_.empty() && in_document_ && !streaming_ && reader_.streamed.count(name_)) {
            streaming_ = true;
            if (reader_.array_begins) reader_.array_begins(name_);
            return true;
        }
        return open(OJson::array());
    }
    bool key(string_t& k) override {
        if (stack_.empty() && !streaming_) {
            name_ = k;
            return true;
        }
        keys_.push_back(k);
        return true;
    }
    bool end_object() override { return close(); }
    bool end_array() override {
        if (stack_.empty() && streaming_) {
            streaming_ = false;
            return true;
        }
        return close();
    }
    bool parse_error(std::size_t, const std::string&,
                     const nlohmann::detail::exception& e) override {
        error = e.what(); // the byte: read_with's (the lexer counts the compacted text)
        at_parse_error = true;
        return false;
    }
    bool at_parse_error = false;

  private:
    bool fail(const std::string& what) {
        error = what + " where a member of the document was expected";
        return false;
    }
    bool open(OJson&& value) {
        if (!in_document_) {
            if (!value.is_object()) return fail("an array");
            in_document_ = true; // the document's own object: its members come one by one
            return true;
        }
        if (stack_.size() >= reader_.max_depth)
            return limit("nested deeper than " + std::to_string(reader_.max_depth) + " levels");
        stack_.push_back(std::move(value));
        return count();
    }
    // Every value of the piece being built counts against the reader's limit.
    bool count() {
        if (stack_.empty() || ++values_ <= reader_.max_piece_values) return true;
        return limit("more than " + std::to_string(reader_.max_piece_values) + " values");
    }
    bool limit(const std::string& what) {
        error = (streaming_ ? "an element of " : "member ") + ("'" + name_ + "'") + " " + what +
                ", past what the document holds";
        return false;
    }
    bool close() {
        if (stack_.empty()) { // the document's end
            in_document_ = false;
            return true;
        }
        OJson done = std::move(stack_.back());
        stack_.pop_back();
        return put(std::move(done));
    }
    bool put(OJson&& value) {
        if (!in_document_) return fail("a value");
        if (!stack_.empty()) {
            if (!value.is_structured() && !count()) return false;
            OJson& parent = stack_.back();
            if (parent.is_object()) {
                parent[keys_.back()] = std::move(value);
                keys_.pop_back();
            } else {
                parent.push_back(std::move(value));
            }
            return true;
        }
        values_ = 0; // the piece is whole
        const bool go = streaming_ ? reader_.element(name_, std::move(value))
                                   : reader_.member(name_, std::move(value));
        if (!go) stopped = true;
        return go;
    }

    const JsonDocumentReader& reader_;
    bool in_document_ = false, streaming_ = false;
    std::string name_;
    std::vector<OJson> stack_;
    std::vector<std::string> keys_;
    size_t values_ = 0; // in the piece being built
};

// The document's bytes as the lexer pulls them, with each run of whitespace outside strings
// read as one space. nlohmann's lexer keeps every byte since its last string or number (for its
// error messages): a gigabyte of blanks after a bracket was a gigabyte held. Tokens are never
// joined (a run still separates them), so the document means the same.
class CompactText {
  public:
    CompactText(std::FILE* file, std::string_view text) : file_(file), text_(text) {
        if (!file_) at_ = text_.data(), end_ = at_ + text_.size();
        settle();
    }
    bool done() const { return at_ == end_; }
    char current() const { return *at_; }
    void next() {
        const char c = *at_;
        step();
        if (string_) {
            if (escaped_)
                escaped_ = false;
            else if (c == '\\')
                escaped_ = true;
            else if (c == '"')
                string_ = false;
        } else if (c == '"') {
            string_ = true;
        } else if (is_space(c)) {
            while (!done() && is_space(*at_))
                step();
            return;
        }
        settle();
    }
    uint64_t consumed() const { return consumed_; } // bytes of the document read, blanks too

  private:
    static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
    void step() {
        ++at_;
        ++consumed_;
        settle();
    }
    void settle() { // refills the buffer from the file when it is used up
        if (at_ != end_ || !file_) return;
        const size_t n = std::fread(buffer_.data(), 1, buffer_.size(), file_);
        at_ = buffer_.data();
        end_ = at_ + n;
    }

    std::FILE* file_;
    std::string_view text_;
    std::array<char, 1 << 16> buffer_{};
    const char* at_ = nullptr;
    const char* end_ = nullptr;
    bool string_ = false, escaped_ = false;
    uint64_t consumed_ = 0;
};

// CompactText as the input iterator nlohmann's sax_parse reads; the end compares equal to an
// iterator whose text is done.
struct CompactIterator {
    using iterator_category = std::input_iterator_tag;
    using value_type = char;
    using difference_type = std::ptrdiff_t;
    using pointer = const char*;
    using reference = char;

    CompactText* text = nullptr; // nullptr: the end
    char operator*() const { return text->current(); }
    CompactIterator& operator++() {
        text->next();
        return *this;
    }
    bool operator==(const CompactIterator& o) const { return at_end() == o.at_end(); }
    bool operator!=(const CompactIterator& o) const { return !(*this == o); }
    bool at_end() const { return !text || text->done(); }
};

JsonReadEnd read_with(CompactText& text, const JsonDocumentReader& reader, std::string* why) {
    PieceBuilder b(reader);
    if (OJson::sax_parse(CompactIterator{&text}, CompactIterator{}, &b)) return JsonReadEnd::Done;
    if (b.stopped) return JsonReadEnd::Stopped;
    if (why) {
        *why = b.error.empty() ? "not a JSON document" : b.error;
        if (b.at_parse_error) *why = "byte " + std::to_string(text.consumed()) + ": " + *why;
    }
    return JsonReadEnd::Malformed;
}

} // namespace

JsonReadEnd read_json_document(std::FILE* in, const JsonDocumentReader& reader, std::string* why) {
    const auto text = std::make_unique<CompactText>(in, std::string_view());
    return read_with(*text, reader, why);
}

JsonReadEnd read_json_document(std::string_view text, const JsonDocumentReader& reader,
                               std::string* why) {
    CompactText compact(nullptr, text);
    return read_with(compact, reader, why);
}

} // namespace watergen
