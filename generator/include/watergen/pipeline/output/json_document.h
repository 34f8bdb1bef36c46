// A large JSON document written piece by piece: a head object's members, then arrays whose
// elements are made and written one at a time. The text is exactly what the whole document's
// dump(2) would be (manifest.json's format), but no writer holds the whole document.
#pragma once

#include <cstdio>
#include <functional>
#include <set>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace watergen {

// Where the text goes, piece by piece.
using WriteText = std::function<void(std::string_view)>;

class JsonDocumentWriter {
  public:
    // Writes `head`'s members (an object with at least one member).
    JsonDocumentWriter(const nlohmann::ordered_json& head, const WriteText& write);
    // A member of the document that is an array, after the head's members and earlier arrays.
    void begin_array(std::string_view name);
    void element(const nlohmann::ordered_json& value);
    void end_array();
    // Closes the document (and its last line).
    void end();

  private:
    const WriteText& write_;
    bool first_ = true;
};

// Reads such a document (any JSON object, in fact) one piece at a time: `member` gets each
// top-level member whole, except those named in `streamed`, whose values must be arrays: their
// elements go to `element` one at a time, so memory holds one element, not the document.
// A callback returns false to stop reading early.
struct JsonDocumentReader {
    std::set<std::string> streamed;
    std::function<bool(const std::string& name, nlohmann::ordered_json&& value)> member;
    std::function<bool(const std::string& array, nlohmann::ordered_json&& element)> element;
    std::function<void(const std::string& array)> array_begins = {}; // a streamed array opens
    // Limits of one piece (a member, or an element of a streamed array): containers nested
    // inside it, and values in it. A document past them is malformed: memory holds one piece,
    // whatever the document says. (Blanks are never held: a run of them is read as one.)
    size_t max_depth = 64;
    size_t max_piece_values = size_t(1) << 22;
};
enum class JsonReadEnd { Done, Stopped, Malformed };
// `why` names the byte and the fault of a malformed document.
JsonReadEnd read_json_document(std::FILE* in, const JsonDocumentReader& reader, std::string* why);
// One of the two above, bound to its input: a reader of a document from its text or its file.
using ReadJsonDocument = std::function<JsonReadEnd(const JsonDocumentReader&, std::string*)>;
JsonReadEnd read_json_document(std::string_view text, const JsonDocumentReader& reader,
                               std::string* why);

} // namespace watergen
