// The structural check of a SPIR-V module (spirv_check.h): header, instruction stream, entry
// points. A single pass over the words; nothing is allocated from a count the module claims.
#include "watergen/runtime/spirv_check.h"

#include <cstdio>
#include <vector>

namespace watergen {

namespace {

constexpr uint32_t kMagic = 0x07230203;
constexpr uint32_t kSwappedMagic = 0x03022307;
constexpr uint32_t kMaxIdBound = 0x3FFFFF; // SPIR-V's universal limit on ids
constexpr uint32_t kOpEntryPoint = 15;
constexpr size_t kHeaderWords = 5;

uint32_t execution_model(ShaderStage s) {
    switch (s) {
    case ShaderStage::Vertex:
        return 0;
    case ShaderStage::Fragment:
        return 4;
    case ShaderStage::Compute:
        return 5;
    case ShaderStage::TessControl:
        return 1;
    case ShaderStage::TessEvaluation:
        return 2;
    }
    return 4;
}

std::string model_name(uint32_t model) {
    switch (model) {
    case 0:
        return "Vertex";
    case 1:
        return "TessellationControl";
    case 2:
        return "TessellationEvaluation";
    case 3:
        return "Geometry";
    case 4:
        return "Fragment";
    case 5:
        return "GLCompute";
    case 6:
        return "Kernel";
    }
    return "execution model " + std::to_string(model);
}

std::string hex(uint32_t v) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%08x", v);
    return buf;
}

// The literal string at words[from, end): its bytes up to the first NUL; nullopt-like empty
// flag `ok` false when no NUL ends it inside the instruction.
std::string literal(std::span<const uint32_t> words, size_t from, size_t end, bool& ok) {
    std::string out;
    for (size_t w = from; w < end; ++w)
        for (int b = 0; b < 4; ++b) {
            const char c = static_cast<char>((words[w] >> (8 * b)) & 0xFF);
            if (c == '\0') {
                ok = true;
                return out;
            }
            out += c;
        }
    ok = false;
    return out;
}

bool fail(std::string* why, const std::string& what) {
    *why = what;
    return false;
}

} // namespace

bool check_spirv(std::span<const uint32_t> words, ShaderStage stage, const std::string& entry_point,
                 std::string* why) {
    const std::string expected =
        std::string("expected the ") + to_string(stage) + " stage's SPIR-V module";
    if (words.size() < kHeaderWords)
        return fail(why, std::to_string(words.size() * 4) +
                             " bytes, shorter than the SPIR-V header; " + expected);
    if (words.size() * 4 > kMaxSpirvBytes)
        return fail(why, std::to_string(words.size() * 4) + " bytes, more than " +
                             std::to_string(kMaxSpirvBytes >> 20) + " MiB; " + expected);
    if (words[0] == kSwappedMagic)
        return fail(why, "SPIR-V in the other byte order (magic " + hex(words[0]) +
                             "); expected words in this machine's byte order");
    if (words[0] != kMagic)
        return fail(why, "magic number " + hex(words[0]) + "; expected 0x07230203 (SPIR-V)");
    const uint32_t version = words[1];
    if ((version & 0xFF0000FF) != 0 || version < 0x00010000 || version > 0x00010600)
        return fail(why, "version word " + hex(version) + "; expected SPIR-V 1.0 to 1.6");
    if (words[3] == 0 || words[3] > kMaxIdBound)
        return fail(why, "id bound " + std::to_string(words[3]) + "; expected 1 to 4194303");
    if (words[4] != 0) return fail(why, "schema word " + hex(words[4]) + "; expected 0");
    const uint32_t wanted = execution_model(stage);
    bool found = false;
    std::string seen;
    for (size_t at = kHeaderWords; at < words.size();) {
        const uint32_t count = words[at] >> 16, opcode = words[at] & 0xFFFF;
        if (count == 0 || count > words.size() - at)
            return fail(why, "instruction at word " + std::to_string(at) + " (opcode " +
                                 std::to_string(opcode) + ") claims " + std::to_string(count) +
                                 " words, " + std::to_string(words.size() - at) +
                                 " left; expected a whole SPIR-V module (truncated or corrupt?)");
        if (opcode == kOpEntryPoint) {
            if (count < 4)
                return fail(why, "OpEntryPoint at word " + std::to_string(at) + " has " +
                                     std::to_string(count) + " words; expected at least 4");
            bool ok = false;
            const std::string name = literal(words, at + 3, at + count, ok);
            if (!ok)
                return fail(why, "OpEntryPoint at word " + std::to_string(at) +
                                     ": its name has no terminating NUL; expected a string");
            const uint32_t model = words[at + 1];
            if (model == wanted && (entry_point.empty() || name == entry_point)) found = true;
            if (seen.size() < 200)
                seen += (seen.empty() ? "" : ", ") + model_name(model) + " " + name;
        }
        at += count;
    }
    if (!found)
        return fail(why, "has no OpEntryPoint " + model_name(wanted) +
                             (entry_point.empty() ? "" : " " + entry_point) +
                             " (its entry points: " + (seen.empty() ? "none" : seen) + "); " +
                             expected);
    return true;
}

} // namespace watergen
