#include "watergen/pipeline/json_document.h"

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
    bool parse_error(std::size_t at, const std::string&,
                     const nlohmann::detail::exception& e) override {
        error = "byte " + std::to_string(at) + ": " + e.what();
        return false;
    }

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
        stack_.push_back(std::move(value));
        return true;
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
            OJson& parent = stack_.back();
            if (parent.is_object()) {
                parent[keys_.back()] = std::move(value);
                keys_.pop_back();
            } else {
                parent.push_back(std::move(value));
            }
            return true;
        }
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
};

template <class Input>
JsonReadEnd read_with(Input&& input, const JsonDocumentReader& reader, std::string* why) {
    PieceBuilder b(reader);
    if (OJson::sax_parse(std::forward<Input>(input), &b)) return JsonReadEnd::Done;
    if (b.stopped) return JsonReadEnd::Stopped;
    if (why) *why = b.error.empty() ? "not a JSON document" : b.error;
    return JsonReadEnd::Malformed;
}

} // namespace

JsonReadEnd read_json_document(std::FILE* in, const JsonDocumentReader& reader, std::string* why) {
    return read_with(in, reader, why);
}

JsonReadEnd read_json_document(std::string_view text, const JsonDocumentReader& reader,
                               std::string* why) {
    return read_with(text, reader, why);
}

} // namespace watergen
