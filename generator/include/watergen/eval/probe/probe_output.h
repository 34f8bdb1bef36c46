// `watergen probe` as a library call: the node of checked inputs (prepare_probe) run on the
// device and on the CPU, its results written as CSV (probe_results_csv), and the summary the
// command prints (summarize_probe).
#pragma once

#include <filesystem>

#include "watergen/eval/draw/draw_device.h"
#include "watergen/eval/probe/probe_table.h"

namespace watergen {

struct ProbeOutput {
    ProbeRun run; // its diagnostics: of the compute shader's build
    ProbeSummary summary;
    std::string error; // the run's or the write's failure
    RunStatus status = RunStatus::Ok;
};

// Cost: run_probe's (one toolchain run, one pipeline, one dispatch, three CPU evaluations).
ProbeOutput write_probe(VulkanRunner& runner, const ProbeInputs& inputs, Language language,
                        bool strict_half, const std::filesystem::path& out);

} // namespace watergen
