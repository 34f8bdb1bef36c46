// Checks shared by the numeric flags of every subcommand.
#include <cmath>

#include <fmt/format.h>

#include "commands.h"

namespace watergen::cli {

CLI::Validator finite_range(double lo, double hi) {
    // CLI::Range lets NaN through (every comparison with NaN is false), and prints its bounds
    // rounded to 6 digits; this one rejects NaN and Inf and prints exact bounds.
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            if (text.empty() || *end != '\0') return fmt::format("'{}' is not a number", text);
            if (!std::isfinite(v) || v < lo || v > hi)
                return fmt::format("{} is out of range; expected a finite number in [{}, {}]", text,
                                   lo, hi);
            return "";
        },
        fmt::format("FLOAT in [{} - {}]", lo, hi));
}

void add_unroll_option(CLI::App& app, LoopUnroll& unroll) {
    app.add_option_function<std::string>(
           "--unroll", [&unroll](const std::string& word) { unroll = *parse_loop_unroll(word); },
           "unroll hint of every loop: hinted (each loop's own, default), all ([[unroll]] / "
           "[unroll]) or none ([[dont_unroll]] / [loop])")
        ->check(CLI::IsMember({"hinted", "all", "none"}));
}

SyntheticScene preset_scene(uint32_t width, uint32_t height, const Preset* preset) {
    SyntheticScene scene = make_synthetic_scene(width, height);
    if (preset)
        for (const auto& [name, values] : preset->values)
            scene.uniforms[name] = values;
    return scene;
}

} // namespace watergen::cli
