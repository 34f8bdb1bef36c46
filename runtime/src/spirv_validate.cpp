// spirv-val on a module before a driver sees it (spirv_check.h): SPIRV-Tools' validator, the
// Vulkan 1.1 rules the generator validates its output with (toolchain/spirv_tools_stage.cpp).
#include <spirv-tools/libspirv.hpp>

#include "watergen/runtime/spirv_check.h"

namespace watergen {

bool validate_spirv(std::span<const uint32_t> words, std::string* why) {
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_1);
    std::string first;
    tools.SetMessageConsumer(
        [&first](spv_message_level_t, const char*, const spv_position_t&, const char* message) {
            if (first.empty() && message) first = message;
        });
    if (tools.Validate(words.data(), words.size())) return true;
    while (!first.empty() && (first.back() == '\n' || first.back() == ' '))
        first.pop_back();
    if (const size_t nl = first.find('\n'); nl != std::string::npos) first.resize(nl);
    *why = "spirv-val: " + (first.empty() ? std::string("rejected") : first) +
           "; expected a valid SPIR-V module";
    return false;
}

} // namespace watergen
