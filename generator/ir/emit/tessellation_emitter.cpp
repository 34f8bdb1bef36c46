#include "watergen/ir/emit/tessellation_emitter.h"

#include <algorithm>
#include <utility>

#include "emitter_internal.h"

namespace watergen {

namespace {

struct PatchStage {
    ShaderStage stage;
    const char* what; // in messages
    // The Varyings the skeleton defines, and the outputs a graph must have (float unless
    // said), for the stage.
    std::vector<std::pair<std::string, Type>> inputs;
    std::vector<std::pair<std::string, Type>> required;
};

const PatchStage& control_stage() {
    static const PatchStage s{ShaderStage::TessControl,
                              "tessellation control",
                              {{"corner_0", Type::Vec2},
                               {"corner_1", Type::Vec2},
                               {"corner_2", Type::Vec2},
                               {"corner_3", Type::Vec2}},
                              {{"outer_0", Type::Float},
                               {"outer_1", Type::Float},
                               {"outer_2", Type::Float},
                               {"outer_3", Type::Float},
                               {"inner_0", Type::Float},
                               {"inner_1", Type::Float}}};
    return s;
}

const PatchStage& evaluation_stage() {
    static const PatchStage s{ShaderStage::TessEvaluation,
                              "tessellation evaluation",
                              {{"grid_xz", Type::Vec2}},
                              {{"position", Type::Vec4}}};
    return s;
}

EmittedShader emit_patch_stage(const PatchStage& stage, const Graph& g, Language language,
                               const std::string& skeleton, const std::string& file_name,
                               const std::string& variant_key, Diagnostics& diagnostics,
                               const PatchStageOptions& options) {
    const std::string name = std::string(to_string(language)) + "/" + skeleton + "." +
                             file_extension(language, stage.stage);
    const std::string_view text = template_text(name);
    auto fail = [&](const std::string& message) {
        diagnostics.push_back({Severity::Error, file_name, 0, 0, "", message});
        EmittedShader out;
        out.language = language;
        out.stage = stage.stage;
        out.file_name = file_name;
        return out;
    };
    if (text.empty())
        return fail(std::string("no ") + stage.what + " skeleton '" + name + "' under templates/");
    if (has_errors(g.diagnostics()))
        return fail(std::string(stage.what) + " graph has type errors");
    for (uint32_t id : g.live_nodes()) {
        const Node& n = g.node(id);
        if (n.op != Op::Varying) continue;
        const bool defined = std::find(stage.inputs.begin(), stage.inputs.end(),
                                       std::pair{n.name, n.type}) != stage.inputs.end();
        if (!defined) {
            std::string expected;
            for (const auto& [input, type] : stage.inputs)
                expected += (expected.empty() ? "" : ", ") + input + " (" + type_name(type) + ")";
            return fail(std::string(stage.what) + " graph reads the input '" + n.name + "' (" +
                        type_name(n.type) + "), which " + name + " does not define; expected " +
                        expected);
        }
    }
    for (const auto& required : stage.required) {
        const auto& outputs = g.outputs();
        // (Not a structured binding: clang before 16 cannot capture one in the lambda.)
        const auto it = std::find_if(outputs.begin(), outputs.end(),
                                     [&](const auto& o) { return o.name == required.first; });
        if (it == outputs.end() || g.node(it->node).type != required.second)
            return fail(std::string(stage.what) + " graph needs a " + type_name(required.second) +
                        " output '" + required.first + "'");
    }
    for (const auto& o : g.outputs()) {
        // A skeleton that never mentions an output would drop it silently.
        if (text.find("{{output_" + o.name + "}}") == std::string_view::npos)
            return fail(std::string(stage.what) + " output '" + o.name + "' is not written by " +
                        name);
        if (!is_float_numeric(g.node(o.node).type))
            return fail(std::string(stage.what) + " output '" + o.name +
                        "' is not a float scalar or vector");
    }
    return emit_from_skeleton(g, language, stage.stage, text, file_name, variant_key, diagnostics,
                              SkeletonOptions{options.bindings, true, options.block});
}

} // namespace

EmittedShader emit_tess_control(const Graph& g, Language language, const std::string& skeleton,
                                const std::string& file_name, const std::string& variant_key,
                                Diagnostics& diagnostics, const PatchStageOptions& options) {
    return emit_patch_stage(control_stage(), g, language, skeleton, file_name, variant_key,
                            diagnostics, options);
}

EmittedShader emit_tess_evaluation(const Graph& g, Language language, const std::string& skeleton,
                                   const std::string& file_name, const std::string& variant_key,
                                   Diagnostics& diagnostics, const PatchStageOptions& options) {
    return emit_patch_stage(evaluation_stage(), g, language, skeleton, file_name, variant_key,
                            diagnostics, options);
}

std::vector<Parameter> shared_block_parameters(const std::vector<const Graph*>& graphs,
                                               Diagnostics& diagnostics) {
    std::vector<Parameter> block;
    for (const Graph* g : graphs)
        for (Parameter& p : parameters_read(*g)) {
            const auto it = std::find_if(block.begin(), block.end(),
                                         [&](const Parameter& b) { return b.name == p.name; });
            if (it == block.end())
                block.push_back(std::move(p));
            else if (!same_definition(*it, p))
                diagnostics.push_back({Severity::Error, "", 0, 0, p.origin,
                                       definition_clash("parameter", p.name, it->origin,
                                                        it->defined_at, p.origin, p.defined_at)});
        }
    return block;
}

} // namespace watergen
