#include "watergen/toolchain/spirv_tools_stage.h"

#include <cstring>
#include <unordered_map>

#include <spirv-tools/libspirv.hpp>
#include <spirv-tools/optimizer.hpp>

namespace watergen {
namespace {

constexpr spv_target_env kEnv = SPV_ENV_VULKAN_1_1;

Severity to_severity(spv_message_level_t level) {
    switch (level) {
    case SPV_MSG_FATAL:
    case SPV_MSG_INTERNAL_ERROR:
    case SPV_MSG_ERROR:
        return Severity::Error;
    case SPV_MSG_WARNING:
        return Severity::Warning;
    case SPV_MSG_INFO:
    case SPV_MSG_DEBUG:
        return Severity::Note;
    }
    return Severity::Error;
}

spvtools::MessageConsumer collect_into(Diagnostics& out, const std::string& file,
                                       const char* tool) {
    return [&out, &file, tool](spv_message_level_t level, const char*, const spv_position_t&,
                               const char* message) {
        std::string text = std::string(tool) + ": " + (message ? message : "");
        while (!text.empty() && text.back() == '\n')
            text.pop_back();
        out.push_back({to_severity(level), file, 0, 0, "", std::move(text)});
    };
}

// Runs the passes `add_passes` registers on `spirv`; `failure` names the step when it fails
// without a diagnostic of its own.
template <class AddPasses>
OptimizeResult run_passes(const std::vector<uint32_t>& spirv, const std::string& file_name,
                          const char* failure, AddPasses add_passes) {
    OptimizeResult result;
    spvtools::Optimizer optimizer(kEnv);
    optimizer.SetMessageConsumer(collect_into(result.diagnostics, file_name, "spirv-opt"));
    add_passes(optimizer);
    spvtools::OptimizerOptions options;
    options.set_run_validator(false);
    if (!optimizer.Run(spirv.data(), spirv.size(), &result.spirv, options)) {
        result.spirv.clear();
        if (!has_errors(result.diagnostics))
            result.diagnostics.push_back({Severity::Error, file_name, 0, 0, "", failure});
    }
    return result;
}

OptimizeResult run_optimizer(const std::vector<uint32_t>& spirv, const std::string& file_name,
                             bool legalize) {
    return run_passes(spirv, file_name,
                      legalize ? "spirv-opt: legalization failed"
                               : "spirv-opt: optimization failed",
                      [legalize](spvtools::Optimizer& o) {
                          if (legalize)
                              o.RegisterLegalizationPasses();
                          else
                              o.RegisterPerformancePasses();
                      });
}

} // namespace

namespace {

// True when the module is valid; the validator's messages go to `ds`.
bool run_validator(const std::vector<uint32_t>& spirv, const std::string& file_name,
                   bool friendly_names, Diagnostics& ds) {
    spvtools::SpirvTools tools(kEnv);
    tools.SetMessageConsumer(collect_into(ds, file_name, "spirv-val"));
    spvtools::ValidatorOptions options;
    options.SetFriendlyNames(friendly_names);
    return tools.Validate(spirv.data(), spirv.size(), options);
}

} // namespace

Diagnostics validate_spirv(const std::vector<uint32_t>& spirv, const std::string& file_name) {
    // Friendly names (%water_height rather than %42) cost one more parse of the module and a
    // string per id: 5.9% of the whole in-process chain over the covering set (callgrind,
    // `watergen bench compile --repeat 1`), for text that only messages show. So validate
    // without them, and only a module with something to say is validated again with them.
    Diagnostics quiet;
    if (run_validator(spirv, file_name, false, quiet) && quiet.empty()) return {};
    Diagnostics ds;
    if (!run_validator(spirv, file_name, true, ds) && !has_errors(ds))
        ds.push_back({Severity::Error, file_name, 0, 0, "", "spirv-val: invalid module"});
    return ds;
}

OptimizeResult optimize_spirv(const std::vector<uint32_t>& spirv, const std::string& file_name) {
    return run_optimizer(spirv, file_name, false);
}

OptimizeResult legalize_spirv(const std::vector<uint32_t>& spirv, const std::string& file_name) {
    return run_optimizer(spirv, file_name, true);
}

OptimizeResult freeze_specialization(const std::vector<uint32_t>& spirv,
                                     const std::map<uint32_t, float>& values,
                                     const std::string& file_name) {
    std::unordered_map<uint32_t, std::vector<uint32_t>> bits;
    for (const auto& [id, v] : values) {
        uint32_t word = 0;
        std::memcpy(&word, &v, sizeof word);
        bits[id] = {word};
    }
    OptimizeResult result =
        run_passes(spirv, file_name, "spirv-opt: freezing failed", [&bits](spvtools::Optimizer& o) {
            o.RegisterPass(spvtools::CreateSetSpecConstantDefaultValuePass(bits))
                .RegisterPass(spvtools::CreateFreezeSpecConstantValuePass())
                .RegisterPass(spvtools::CreateFoldSpecConstantOpAndCompositePass())
                .RegisterPass(spvtools::CreateUnifyConstantPass())
                .RegisterPerformancePasses();
        });
    if (result.spirv.empty()) return result;
    Diagnostics invalid = validate_spirv(result.spirv, file_name);
    if (has_errors(invalid)) result.spirv.clear();
    result.diagnostics.insert(result.diagnostics.end(), invalid.begin(), invalid.end());
    return result;
}

size_t count_instructions(const std::vector<uint32_t>& spirv) {
    constexpr size_t kHeaderWords = 5;
    size_t count = 0;
    size_t i = kHeaderWords;
    while (i < spirv.size()) {
        const uint32_t words = spirv[i] >> 16;
        if (words == 0 || i + words > spirv.size()) break; // malformed: stop, don't loop forever
        ++count;
        i += words;
    }
    return count;
}

bool declares_capability(const std::vector<uint32_t>& spirv, uint32_t capability) {
    constexpr uint32_t kOpCapability = 17;
    for (size_t i = 5; i < spirv.size();) {
        const uint32_t words = spirv[i] >> 16;
        if (words == 0 || i + words > spirv.size()) break;
        // Capabilities come first (SPIR-V 2.4, logical layout): stop at the first other opcode.
        if ((spirv[i] & 0xffff) != kOpCapability) break;
        if (words >= 2 && spirv[i + 1] == capability) return true;
        i += words;
    }
    return false;
}

std::string disassemble_spirv(const std::vector<uint32_t>& spirv) {
    spvtools::SpirvTools tools(kEnv);
    std::string text;
    const uint32_t options =
        SPV_BINARY_TO_TEXT_OPTION_FRIENDLY_NAMES | SPV_BINARY_TO_TEXT_OPTION_INDENT;
    if (!tools.Disassemble(spirv, &text, options)) return {};
    return text;
}

} // namespace watergen
