#include "watergen/pipeline/manifest/manifest_files.h"

#include "watergen/pipeline/output/json_document.h"
#include "watergen/pipeline/output/output_writer.h"
#include "watergen/runtime/manifest_schema.h"

namespace watergen {

using OJson = nlohmann::ordered_json;
namespace mk = manifest_schema;

namespace {

bool starts_with(const std::string& s, const std::string& prefix) {
    return s.compare(0, prefix.size(), prefix) == 0;
}

// The paths under one "files" object ({kind: [path, ...]}) below `directory`; "" or why not.
std::string files_under(const OJson& files, const std::string& directory,
                        std::vector<std::string>& paths) {
    if (!files.is_object()) return "\"files\" is not an object of path lists";
    for (const auto& [kind, list] : files.items()) {
        if (!list.is_array()) return "\"files\"/" + kind + " is not a list of paths";
        for (const OJson& p : list) {
            if (!p.is_string() || !is_plain_relative_path(p.get<std::string>()) ||
                !starts_with(p.get<std::string>(), directory + "/"))
                return "\"files\"/" + kind + " names " + p.dump() +
                       "; expected a plain relative path inside \"" + directory + "\"";
            paths.push_back(p);
        }
    }
    return "";
}

} // namespace

std::string named_files(const OJson& entry, std::vector<std::string>& paths) {
    if (!entry.is_object()) return "an entry is not an object";
    // A variant's or a shader's "files" and "directory" (namespace output) and a pass's (pass)
    // are spelled alike.
    if (entry.contains(mk::output::kFiles) || entry.contains(mk::output::kDirectory)) {
        const OJson dir = entry.value(mk::output::kDirectory, OJson());
        if (!dir.is_string() || !is_plain_relative_path(dir.get<std::string>()))
            return "\"directory\" " + dir.dump() + " is not a plain relative path";
        if (std::string why =
                files_under(entry.value(mk::output::kFiles, OJson::object()), dir, paths);
            !why.empty())
            return why;
    }
    // A variant a specialized build freezes: its own SPIR-V per language, in its shader's
    // directory.
    if (const auto it = entry.find(mk::variant::kFrozen); it != entry.end()) {
        const OJson shader = entry.value(mk::variant::kShader, OJson());
        if (!it->is_object() || !shader.is_string())
            return "\"frozen\" is not an object of paths beside a \"shader\"";
        for (const auto& [lang, p] : it->items()) {
            if (!p.is_string() || !is_plain_relative_path(p.get<std::string>()) ||
                !starts_with(p.get<std::string>(), shader.get<std::string>() + "/"))
                return "\"frozen\"/" + lang + " names " + p.dump() +
                       "; expected a plain relative path inside \"" + shader.get<std::string>() +
                       "\"";
            paths.push_back(p);
        }
    }
    if (const auto it = entry.find(mk::variant::kPasses); it != entry.end()) {
        if (!it->is_object()) return "\"passes\" is not an object";
        for (const auto& [name, pass] : it->items())
            if (std::string why = named_files(pass, paths); !why.empty())
                return "pass " + name + ": " + why;
    }
    return "";
}

namespace {

template <class Input>
std::string named_files_of(Input&& in, const std::function<void(std::string&&)>& each) {
    bool variants = false;
    std::string why;
    // A modes build's shaders hold the files; its variants name their frozen modules.
    JsonDocumentReader reader{
        {mk::top::kVariants, mk::top::kShaders},
        [&](const std::string& name, OJson&&) {
            if (name != mk::top::kVariants && name != mk::top::kShaders) return true;
            why = "\"" + name + "\" is not a list";
            return false;
        },
        [&](const std::string&, OJson&& v) {
            std::vector<std::string> paths;
            why = named_files(v, paths);
            for (std::string& p : paths)
                each(std::move(p));
            return why.empty();
        },
        [&](const std::string& array) { variants = variants || array == mk::top::kVariants; }};
    std::string malformed;
    if (read_json_document(std::forward<Input>(in), reader, &malformed) == JsonReadEnd::Malformed)
        return "manifest.json is not the manifest of a build (" + malformed + ")";
    if (!why.empty()) return why;
    if (!variants) return "manifest.json is not the manifest of a build";
    return "";
}

} // namespace

std::string manifest_named_files(const std::string& bytes, std::vector<std::string>& paths) {
    return named_files_of(std::string_view(bytes),
                          [&](std::string&& p) { paths.push_back(std::move(p)); });
}

std::string manifest_named_files(std::FILE* in, const std::function<void(std::string&&)>& each) {
    return named_files_of(in, each);
}

} // namespace watergen
