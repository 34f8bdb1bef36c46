// Build benchmark as a library call (`watergen bench build` prints it): variants per second of
// `watergen build`, cold (empty cache), warm (the build again, every variant from the cache) and
// no-op (again, with the build record: nothing changed, the output verified, no IR work), on one
// thread and on all, for the full space and for a pruned example (a material and its scenes).
//
// The full space is far too large to compile in a benchmark, so for it the bench measures
// (1) enumerating it and checking its rules, (2) planning each given scene over it (which
// variants the scene reaches), both over the whole space, and (3) building an evenly spaced
// sample of it (every k-th variant in enumeration order) through the same jobs as
// `watergen build` (compose, emit, hash, cache or toolchain), without writing files. The
// pruned example is a complete `watergen build`, output written to a scratch directory.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "watergen/plan/material.h"
#include "watergen/plan/scene_file.h"

namespace watergen {

struct BuildBenchRow {
    std::string what;
    size_t variants = 0;
    double seconds = 0;
    std::string note;
    double rate() const { return seconds > 0 ? variants / seconds : 0.0; } // variants per second
};

struct BuildBenchRequest {
    Material example;               // the pruned example's material
    std::vector<SceneFacts> scenes; // and its scenes (none: unpruned)
    unsigned threads = 0;           // threads of the "all threads" runs; 0: every hardware thread
    size_t sample = 48;             // full-space variants to build, evenly spaced
    std::filesystem::path
        work; // scratch directory, removed at the end; "" for one under the temp dir
};

struct BuildBenchResult {
    std::vector<BuildBenchRow> rows; // in the order measured
    std::string csv, json;           // build.csv, build.json
    Diagnostics diagnostics; // why the pruned example failed to build (then rows are incomplete)
    bool ok() const { return !has_errors(diagnostics); }
};

// Cost: the sample built four times and the example four times (cold runs compile every
// distinct shader), plus enumerating and planning the full space.
BuildBenchResult bench_build(const BuildBenchRequest& request);

} // namespace watergen
