// --target: which compiler a cost comes from (gpu_target.h), shared by every cost-based command.
#include <cstdio>
#include <set>

#include "commands.h"

namespace watergen::cli {

void add_target_option(CLI::App& app, std::vector<std::string>& targets) {
    app.add_option("--target", targets,
                   "cost target, repeatable or a comma list: " + gpu_target_names() +
                       " (default lavapipe). AMD families compile through ACO on RADV's null "
                       "device (mesa-vulkan-drivers), no GPU needed; steamdeck is rdna2's ISA")
        ->take_all();
}

std::optional<std::vector<GpuTarget>> resolve_targets(const std::vector<std::string>& words,
                                                      const std::string& flag) {
    std::string error;
    auto targets = parse_gpu_targets(words.empty() ? std::vector<std::string>{"lavapipe"} : words,
                                     &error, flag);
    if (!targets) std::fprintf(stderr, "watergen: error: %s\n", error.c_str());
    return targets;
}

int check_target_runs(const std::vector<TargetCosts>& runs) {
    int code = kOk;
    for (const auto& t : runs) {
        if (t.run.ok()) continue;
        std::fprintf(stderr, "watergen: error: %s\n", t.run.error.c_str());
        if (t.run.no_device)
            code = kNoDevice;
        else if (code == kOk)
            code = kFailed;
    }
    return code;
}

std::string cost_unit(const GpuTarget& target) {
    if (target.is_lavapipe()) return "instructions per pixel lavapipe executes (valgrind)";
    return target.name + " fragment instructions per pixel (ACO, loops weighted by trip count)";
}

void print_gpu_costs(const TargetCosts& t) {
    const GpuTarget& g = t.run.target;
    std::printf("%s: %s, %s (ACO on RADV's null device%s)\n", g.name.c_str(), g.isa.c_str(),
                t.run.device.c_str(),
                g.alias_of.empty() ? "" : (", the same code as " + g.alias_of).c_str());
    std::printf("  %-28s %-15s %7s %9s %5s %5s %7s %7s %6s %6s %8s %8s\n", "pipeline", "stage",
                "instr", "per-pixel", "VGPR", "SGPR", "spills", "scratch", "code", "waves",
                "latency", "inv-thr");
    for (const auto& c : t.costs) {
        if (!c.ok()) {
            std::printf("  %-28s refused: %s\n", c.name.c_str(), c.error.c_str());
            continue;
        }
        for (const auto& s : c.stages) {
            const std::string per_pixel =
                s.per_pixel ? std::to_string(static_cast<long long>(*s.per_pixel)) : "-";
            std::printf("  %-28s %-15s %7.0f %9s %5.0f %5.0f %7.0f %7.0f %6.0f %6.0f %8.0f %8.0f\n",
                        c.name.c_str(), s.stage.c_str(), s.instructions, per_pixel.c_str(), s.vgprs,
                        s.sgprs, s.spilled_vgprs + s.spilled_sgprs, s.scratch_bytes, s.code_bytes,
                        s.waves_per_simd, s.latency, s.inverse_throughput);
        }
    }
    // Why an estimate is missing, once per distinct reason.
    std::set<std::string> notes;
    for (const auto& c : t.costs)
        for (const auto& s : c.stages)
            if (!s.per_pixel && notes.insert(s.stage + ": " + s.per_pixel_note).second)
                std::printf("  no per-pixel estimate for the %s stage: %s\n", s.stage.c_str(),
                            s.per_pixel_note.c_str());
}

} // namespace watergen::cli
