#include "watergen/toolchain/glslang_stage.h"

#include <algorithm>
#include <charconv>
#include <map>
#include <mutex>
#include <set>
#include <string_view>

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <glslang/SPIRV/Logger.h>

#include "watergen/toolchain/spirv_tools_stage.h"

namespace watergen {
namespace {

EShLanguage to_glslang(ShaderStage stage) {
    switch (stage) {
    case ShaderStage::Vertex:
        return EShLangVertex;
    case ShaderStage::Fragment:
        return EShLangFragment;
    case ShaderStage::Compute:
        return EShLangCompute;
    case ShaderStage::TessControl:
        return EShLangTessControl;
    case ShaderStage::TessEvaluation:
        return EShLangTessEvaluation;
    }
    return EShLangFragment;
}

// glslang keeps process-wide tables; InitializeProcess must run before any TShader exists.
void ensure_initialized() {
    static std::once_flag flag;
    std::call_once(flag, [] { glslang::InitializeProcess(); });
}

bool parse_int(std::string_view text, int& out) {
    if (text.empty()) return false;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
    return ec == std::errc() && end == text.data() + text.size();
}

// "0:12" / "0:12:5" (string index, line, optional column) -> line, column.
bool parse_location(std::string_view loc, int& line, int& column) {
    std::vector<std::string_view> parts;
    size_t start = 0;
    for (size_t i = 0; i <= loc.size(); ++i) {
        if (i == loc.size() || loc[i] == ':') {
            parts.push_back(loc.substr(start, i - start));
            start = i + 1;
        }
    }
    if (parts.size() == 2) {
        column = 0;
        return parse_int(parts[1], line);
    }
    if (parts.size() == 3) return parse_int(parts[1], line) && parse_int(parts[2], column);
    return false;
}

bool is_error_summary(std::string_view message) {
    // "1 compilation errors.  No code generated." repeats what the real errors said.
    size_t digits = 0;
    while (digits < message.size() && message[digits] >= '0' && message[digits] <= '9')
        ++digits;
    return digits > 0 && message.substr(digits).starts_with(" compilation errors.");
}

void append_all(Diagnostics& to, Diagnostics from) {
    for (auto& d : from)
        to.push_back(std::move(d));
}

// A failed glslang call must never come back without an error to show.
void ensure_error(Diagnostics& ds, const std::string& file, const char* what) {
    if (!has_errors(ds)) ds.push_back({Severity::Error, file, 0, 0, "", what});
}

// --- HLSL varying names -------------------------------------------------------------
// glslang names flattened HLSL entry-point structs "@entryPointOutput.uv" / "input.uv".
// GLSL 330 and ESSL 300 link varyings by NAME, so SPIRV-Cross's "_entryPointOutput_uv"
// in the vertex shader would never meet "uv" in the fragment shader. Rename varyings
// (vertex outputs, fragment inputs) to their last component when that stays unique.

constexpr uint32_t kOpName = 5;
constexpr uint32_t kOpVariable = 59;
constexpr uint32_t kStorageInput = 1;
constexpr uint32_t kStorageOutput = 3;
constexpr size_t kHeaderWords = 5;

std::string decode_string(const uint32_t* words, size_t count) {
    std::string out;
    for (size_t i = 0; i < count; ++i)
        for (int b = 0; b < 4; ++b) {
            const char c = char((words[i] >> (8 * b)) & 0xffu);
            if (c == 0) return out;
            out.push_back(c);
        }
    return out;
}

void encode_op_name(uint32_t target, const std::string& name, std::vector<uint32_t>& out) {
    const size_t string_words = name.size() / 4 + 1; // always room for the terminating 0
    out.push_back(uint32_t((2 + string_words) << 16) | kOpName);
    out.push_back(target);
    for (size_t w = 0; w < string_words; ++w) {
        uint32_t word = 0;
        for (size_t b = 0; b < 4; ++b) {
            const size_t i = w * 4 + b;
            if (i < name.size()) word |= uint32_t(uint8_t(name[i])) << (8 * b);
        }
        out.push_back(word);
    }
}

void rename_hlsl_varyings(std::vector<uint32_t>& spirv, ShaderStage stage) {
    uint32_t varying_class = 0;
    // A domain stage's outputs are what the fragment stage reads, as a vertex stage's are.
    if (stage == ShaderStage::Vertex || stage == ShaderStage::TessEvaluation)
        varying_class = kStorageOutput;
    else if (stage == ShaderStage::Fragment)
        varying_class = kStorageInput;
    else
        return;

    std::map<uint32_t, uint32_t> storage; // interface variable id -> storage class
    std::map<uint32_t, std::string> names;
    for (size_t i = kHeaderWords; i < spirv.size();) {
        const uint32_t count = spirv[i] >> 16, op = spirv[i] & 0xffffu;
        if (count == 0 || i + count > spirv.size()) return; // malformed: leave it alone
        if (op == kOpVariable && count >= 4 &&
            (spirv[i + 3] == kStorageInput || spirv[i + 3] == kStorageOutput))
            storage[spirv[i + 2]] = spirv[i + 3];
        if (op == kOpName && count >= 3)
            names[spirv[i + 1]] = decode_string(&spirv[i + 2], count - 2);
        i += count;
    }

    std::set<std::string> taken;
    for (const auto& [id, cls] : storage)
        if (names.count(id)) taken.insert(names[id]);
    std::map<uint32_t, std::string> renamed;
    for (const auto& [id, cls] : storage) {
        if (cls != varying_class || !names.count(id)) continue;
        const std::string& old_name = names[id];
        const size_t dot = old_name.rfind('.');
        if (dot == std::string::npos || dot + 1 == old_name.size()) continue;
        const std::string new_name = old_name.substr(dot + 1);
        if (!taken.insert(new_name).second) continue;
        renamed[id] = new_name;
    }
    if (renamed.empty()) return;

    std::vector<uint32_t> out(spirv.begin(), spirv.begin() + kHeaderWords);
    out.reserve(spirv.size());
    for (size_t i = kHeaderWords; i < spirv.size();) {
        const uint32_t count = spirv[i] >> 16, op = spirv[i] & 0xffffu;
        const auto it = op == kOpName ? renamed.find(spirv[i + 1]) : renamed.end();
        if (it != renamed.end())
            encode_op_name(it->first, it->second, out);
        else
            out.insert(out.end(), spirv.begin() + long(i), spirv.begin() + long(i + count));
        i += count;
    }
    spirv = std::move(out);
}

SpirvResult compile_impl(const CompileRequest& request) {
    ensure_initialized();
    SpirvResult result;
    const bool hlsl = request.language == SourceLanguage::Hlsl;
    const EShLanguage stage = to_glslang(request.stage);

    glslang::TShader shader(stage);
    const char* text = request.source.c_str();
    shader.setStrings(&text, 1);
    shader.setEnvInput(hlsl ? glslang::EShSourceHlsl : glslang::EShSourceGlsl, stage,
                       glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_1);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_3);
    if (hlsl) shader.setEntryPoint(request.entry_point.c_str());

    // The same message set glslangValidator uses for -V (plus -D for HLSL).
    int flags = EShMsgSpvRules | EShMsgVulkanRules;
    if (hlsl) flags |= EShMsgReadHlsl;
    if (hlsl && request.hlsl_16bit_types) flags |= EShMsgHlslEnable16BitTypes;
    const auto messages = static_cast<EShMessages>(flags);

    const bool parsed = shader.parse(GetDefaultResources(), hlsl ? 100 : 450,
                                     hlsl ? ENoProfile : ECoreProfile, false, false, messages);
    append_all(result.diagnostics, parse_glslang_log(shader.getInfoLog(), request.file_name));
    if (!parsed) {
        ensure_error(result.diagnostics, request.file_name, "glslang: compilation failed");
        return result;
    }

    // Declared after the shader so it is destroyed first: it points into the shader.
    glslang::TProgram program;
    program.addShader(&shader);
    const bool linked = program.link(messages) && program.mapIO();
    append_all(result.diagnostics, parse_glslang_log(program.getInfoLog(), request.file_name));
    if (!linked) {
        ensure_error(result.diagnostics, request.file_name, "glslang: link failed");
        return result;
    }

    spv::SpvBuildLogger logger;
    glslang::SpvOptions options;
    // Optimisation is a later, separate stage; legalisation (HLSL) is done below so its
    // messages become diagnostics instead of glslang printing them to stderr.
    options.disableOptimizer = true;
    glslang::GlslangToSpv(*program.getIntermediate(stage), result.spirv, &logger, &options);
    const std::string spv_log = logger.getAllMessages();
    if (!spv_log.empty())
        result.diagnostics.push_back({Severity::Warning, request.file_name, 0, 0, "", spv_log});

    if (hlsl && !result.spirv.empty()) {
        OptimizeResult legal = legalize_spirv(result.spirv, request.file_name);
        append_all(result.diagnostics, std::move(legal.diagnostics));
        result.spirv = std::move(legal.spirv);
        rename_hlsl_varyings(result.spirv, request.stage);
    }
    if (result.spirv.empty())
        ensure_error(result.diagnostics, request.file_name, "glslang: no SPIR-V produced");
    return result;
}

// Returns the line number and "#version" tokens of the first #version directive.
struct VersionLine {
    int line = 0;
    std::string number;
    std::string profile;
};

VersionLine find_version_line(const std::string& source) {
    VersionLine v;
    int line = 1;
    size_t pos = 0;
    while (pos <= source.size()) {
        size_t end = source.find('\n', pos);
        if (end == std::string::npos) end = source.size();
        std::string_view l(source.data() + pos, end - pos);
        const size_t first = l.find_first_not_of(" \t");
        if (first != std::string_view::npos && l.substr(first).starts_with("#version")) {
            v.line = line;
            std::string_view rest = l.substr(first + 8);
            std::vector<std::string> tokens;
            size_t i = 0;
            while (i < rest.size()) {
                while (i < rest.size() && (rest[i] == ' ' || rest[i] == '\t' || rest[i] == '\r'))
                    ++i;
                size_t j = i;
                while (j < rest.size() && rest[j] != ' ' && rest[j] != '\t' && rest[j] != '\r')
                    ++j;
                if (j > i) tokens.emplace_back(rest.substr(i, j - i));
                i = j;
            }
            if (!tokens.empty()) v.number = tokens[0];
            if (tokens.size() > 1) v.profile = tokens[1];
            return v;
        }
        pos = end + 1;
        ++line;
    }
    return v;
}

} // namespace

Diagnostics parse_glslang_log(const std::string& log, const std::string& file_name) {
    static constexpr struct {
        std::string_view prefix;
        Severity severity;
    } kPrefixes[] = {
        {"ERROR: ", Severity::Error},
        {"WARNING: ", Severity::Warning},
        {"INTERNAL ERROR: ", Severity::Error},
        {"UNIMPLEMENTED: ", Severity::Error},
        {"NOTE: ", Severity::Note},
    };
    Diagnostics out;
    size_t pos = 0;
    while (pos < log.size()) {
        size_t end = log.find('\n', pos);
        if (end == std::string::npos) end = log.size();
        std::string_view line(log.data() + pos, end - pos);
        pos = end + 1;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        if (line.find_first_not_of(" \t") == std::string_view::npos) continue;

        const auto* match = std::find_if(std::begin(kPrefixes), std::end(kPrefixes),
                                         [&](const auto& p) { return line.starts_with(p.prefix); });
        if (match == std::end(kPrefixes)) {
            // glslang continues some messages on following lines.
            if (!out.empty())
                out.back().message.append("\n").append(line);
            else
                out.push_back({Severity::Note, file_name, 0, 0, "", std::string(line)});
            continue;
        }
        std::string_view rest = line.substr(match->prefix.size());
        Diagnostic d{match->severity, file_name, 0, 0, "", ""};
        const size_t colon_space = rest.find(": ");
        int l = 0, c = 0;
        if (colon_space != std::string_view::npos &&
            parse_location(rest.substr(0, colon_space), l, c)) {
            d.line = l;
            d.column = c;
            rest = rest.substr(colon_space + 2);
        } else if (is_error_summary(rest)) {
            continue;
        }
        // glslang pads some messages with a trailing space.
        while (!rest.empty() && (rest.back() == ' ' || rest.back() == '\t'))
            rest.remove_suffix(1);
        d.message = std::string(rest);
        out.push_back(std::move(d));
    }
    return out;
}

void glslang_warm_up() {
    ensure_initialized();
    static std::once_flag flag;
    std::call_once(flag, [] {
        CompileRequest tiny;
        tiny.stage = ShaderStage::Fragment;
        tiny.file_name = "<warm-up>";
        tiny.source =
            "#version 450\nlayout(location = 0) out vec4 c;\nvoid main() { c = vec4(1.0); }\n";
        (void)compile_impl(tiny);
    });
}

SpirvResult compile_to_spirv(const CompileRequest& request) {
    glslang_warm_up();
    return compile_impl(request);
}

Diagnostics check_glsl(const std::string& source, ShaderStage stage, GlslProfile profile,
                       const std::string& file_name) {
    ensure_initialized();
    Diagnostics ds;
    const bool es = profile == GlslProfile::Es300;
    const VersionLine v = find_version_line(source);
    const bool version_ok = es ? (v.number == "300" && v.profile == "es")
                               : (v.number == "330" && (v.profile.empty() || v.profile == "core"));
    if (!version_ok) {
        ds.push_back({Severity::Error, file_name, v.line, 0, "",
                      std::string("expected '#version ") + (es ? "300 es'" : "330' (core)") +
                          (v.line == 0 ? ", found no #version line"
                                       : ", found '#version " + v.number +
                                             (v.profile.empty() ? "" : " " + v.profile) + "'")});
    }

    const EShLanguage lang = to_glslang(stage);
    glslang::TShader shader(lang);
    const char* text = source.c_str();
    shader.setStrings(&text, 1);
    // No client and no target: plain OpenGL / OpenGL ES rules, nothing Vulkan-specific.
    shader.setEnvInput(glslang::EShSourceGlsl, lang, glslang::EShClientNone, 0);
    const bool parsed = shader.parse(GetDefaultResources(), es ? 300 : 330,
                                     es ? EEsProfile : ECoreProfile, false, false, EShMsgDefault);
    append_all(ds, parse_glslang_log(shader.getInfoLog(), file_name));
    if (!parsed) {
        ensure_error(ds, file_name, "glslang: GLSL does not compile");
        return ds;
    }
    glslang::TProgram program;
    program.addShader(&shader);
    const bool linked = program.link(EShMsgDefault);
    append_all(ds, parse_glslang_log(program.getInfoLog(), file_name));
    if (!linked) ensure_error(ds, file_name, "glslang: GLSL does not link");
    return ds;
}

} // namespace watergen
