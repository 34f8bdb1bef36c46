#include "watergen/ir/emit/vertex_emitter.h"

#include "emitter_internal.h"

namespace watergen {

EmittedShader emit_vertex(const Graph& g, Language language, const std::string& skeleton,
                          const std::string& file_name, const std::string& variant_key,
                          Diagnostics& diagnostics, const BindingMap* bindings,
                          const std::vector<Parameter>* block) {
    const std::string name = std::string(to_string(language)) + "/" + skeleton + "." +
                             file_extension(language, ShaderStage::Vertex);
    const std::string_view text = template_text(name);
    auto fail = [&](const std::string& message) {
        diagnostics.push_back({Severity::Error, file_name, 0, 0, "", message});
        EmittedShader out;
        out.language = language;
        out.stage = ShaderStage::Vertex;
        out.file_name = file_name;
        return out;
    };
    if (text.empty()) return fail("no vertex skeleton '" + name + "' under templates/");
    bool position = false;
    for (const auto& o : g.outputs()) {
        const Type t = g.node(o.node).type;
        if (o.name == "position") position = t == Type::Vec4;
        // A skeleton that never mentions an output would drop it silently.
        if (text.find("{{output_" + o.name + "}}") == std::string_view::npos)
            return fail("vertex output '" + o.name + "' is not written by " + name);
        if (!is_float_numeric(t))
            return fail("vertex output '" + o.name + "' is not a float scalar or vector");
    }
    if (!position) return fail("vertex graph needs a vec4 output 'position' (clip space)");
    if (has_errors(g.diagnostics())) return fail("vertex graph has type errors");
    return emit_from_skeleton(g, language, ShaderStage::Vertex, text, file_name, variant_key,
                              diagnostics, SkeletonOptions{bindings, false, block});
}

} // namespace watergen
