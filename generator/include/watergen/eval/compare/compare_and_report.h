// `watergen compare` as a library call, after plan_compare(): the variants run side by side
// against the reference (run_compare), each caustics variant over its own pass's map
// (compare_caustics.h, the passes then timed), the instruction cost of every variant and the
// reference's A/A pair counted under valgrind (draw_cost.h), and the report (compare_report.h)
// assembled and written into the setup's --out.
#pragma once

#include <string>
#include <vector>

#include "watergen/eval/compare/compare_caustics.h"
#include "watergen/eval/compare/compare_run.h"
#include "watergen/eval/compare/compare_setup.h"

namespace watergen {

struct CompareOutcome {
    CompareRun run; // costs filled in when counted
    // The caustics passes the variants read, timed in the first view (the first's A/A), and
    // the note the report shows above them; none when no variant has a pass.
    std::vector<ComparedCausticsPass> caustics;
    RatioInterval caustics_aa;
    std::string caustics_note;
    // What stopped the run before the report: a variant that did not build (its diagnostics),
    // a failed render, pass timing or instruction count (error).
    Diagnostics diagnostics;
    std::string error;
    std::string write_error; // the report could not be written (the measurements stand)
    RunStatus status = RunStatus::Ok;
    bool measured() const { return error.empty() && !has_errors(diagnostics); }
};

// Cost: run_compare's, the passes' draws and timing rounds, and (spec.cost) about 5 s of JIT
// under valgrind per variant.
CompareOutcome compare_and_report(VulkanRunner& runner, const CompareSetup& setup);

} // namespace watergen
