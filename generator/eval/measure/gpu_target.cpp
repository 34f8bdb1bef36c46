#include "watergen/eval/measure/gpu_target.h"

#include <algorithm>

namespace watergen {

const std::vector<GpuTarget>& gpu_targets() {
    // RADV_FORCE_FAMILY names Mesa 22.3 knows (radv_null_winsys / ac_gpu_info): one chip per
    // architecture, the one its users most often ship on.
    static const std::vector<GpuTarget> targets = {
        {"lavapipe", "", "Mesa's CPU rasterizer (LLVM x86-64 code)", "", true},
        {"gcn1", "tahiti", "GCN1 (gfx6, Radeon HD 7970)", "", false},
        {"gcn4", "polaris10", "GCN4 (gfx8, Radeon RX 480)", ""},
        {"gfx9", "vega10", "GCN5 (gfx9, Radeon RX Vega 64)", ""},
        {"rdna1", "navi10", "RDNA1 (gfx10.1, Radeon RX 5700 XT)", ""},
        {"rdna2", "navi21", "RDNA2 (gfx10.3, Radeon RX 6800 XT)", ""},
        {"rdna3", "gfx1100", "RDNA3 (gfx11, Radeon RX 7900 XTX)", ""},
        {"steamdeck", "navi21", "Steam Deck (Van Gogh: RDNA2's gfx10.3 instruction set)", "rdna2"},
    };
    return targets;
}

const GpuTarget* find_gpu_target(const std::string& name) {
    for (const auto& t : gpu_targets())
        if (t.name == name) return &t;
    return nullptr;
}

std::string gpu_target_names() {
    std::string out;
    for (const auto& t : gpu_targets())
        out += (out.empty() ? "" : ", ") + t.name;
    return out;
}

std::string amd_target_names() {
    std::string out;
    for (const auto& t : gpu_targets())
        if (!t.is_lavapipe()) out += (out.empty() ? "" : ", ") + t.name;
    return out;
}

std::optional<std::vector<GpuTarget>> parse_gpu_targets(const std::vector<std::string>& words,
                                                        std::string* error,
                                                        const std::string& flag) {
    std::vector<GpuTarget> out;
    for (const std::string& word : words) {
        // Every name between commas, the empty ones too ("a,", ",,"; getline drops a last one).
        for (size_t begin = 0;;) {
            const size_t comma = word.find(',', begin);
            const std::string name = word.substr(begin, comma - begin);
            if (name.empty()) {
                *error = flag + " '" + word + "': an empty target name; expected one of " +
                         gpu_target_names();
                return std::nullopt;
            }
            const GpuTarget* t = find_gpu_target(name);
            if (!t) {
                *error = flag + " " + name + ": not a target (one of " + gpu_target_names() + ")";
                return std::nullopt;
            }
            if (std::none_of(out.begin(), out.end(),
                             [&](const GpuTarget& o) { return o.name == t->name; }))
                out.push_back(*t);
            if (comma == std::string::npos) break;
            begin = comma + 1;
        }
    }
    return out;
}

std::vector<GpuTarget> amd_targets(const std::vector<GpuTarget>& targets) {
    std::vector<GpuTarget> out;
    for (const GpuTarget& t : targets)
        if (!t.is_lavapipe()) out.push_back(t);
    return out;
}

bool has_lavapipe(const std::vector<GpuTarget>& targets) {
    return std::any_of(targets.begin(), targets.end(),
                       [](const GpuTarget& t) { return t.is_lavapipe(); });
}

} // namespace watergen
