// `watergen build` from its files as a library call: the inputs hashed, the depfile written, the
// build record checked before anything is loaded (nothing changed and the output intact: a
// no-op), then the material and scene files loaded and built (build_output.h).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "watergen/pipeline/build/build_output.h"

namespace watergen {

struct BuildFilesRequest {
    std::string material_path; // "": the built-in default material
    std::vector<std::string> scene_paths;
    std::filesystem::path out;
    BuildMode mode = BuildMode::Permutations;
    bool freeze = false; // specialized mode only
    Shard shard = {};    // permutations mode only
    BuildOptions options;
    // A binding profile's name or a binding map file (plan/binding_map_file.h); "": the
    // watergen profile. A file is an input like the material: hashed, and in the depfile.
    std::string bindings;
    // Also a Makefile-style dependency file: target <out>/manifest.json, prerequisites the
    // material and scene files. "": none.
    std::string depfile;
};

struct BuildFilesRun {
    BuildSummary summary;         // of the build, or of the no-op (summary.up_to_date)
    bool built = false;           // the files loaded and the build ran
    Diagnostics load_diagnostics; // why the material or a scene file did not load (exit 2)
    std::string depfile_error;    // the depfile was refused or not written: nothing built
    bool depfile_refused = false; // refused (exit 2: depfile_refusal, a path it cannot name)
};

BuildFilesRun build_from_files(const BuildFilesRequest& request);

} // namespace watergen
