#include "watergen/pipeline/build_files.h"

#include "watergen/pipeline/build_record.h"
#include "watergen/pipeline/depfile.h"
#include "watergen/plan/scene_file.h"

namespace watergen {

BuildFilesRun build_from_files(const BuildFilesRequest& files) {
    BuildFilesRun run;
    BuildRequest request;
    request.mode = files.mode;
    request.freeze = files.freeze;
    request.shard = files.shard;
    // Hashed before they are loaded: a file changed in between makes the record stale, never
    // wrong.
    request.inputs_hash =
        build_inputs_hash(files.material_path, files.scene_paths,
                          std::string(to_string(files.mode)) + (files.freeze ? " freeze" : ""))
            .value_or("");
    request.out = files.out;
    request.options = files.options;
    // Written before the build: it depends on the inputs only, and a depfile that cannot be
    // written stops the build before anything else is.
    if (!files.depfile.empty()) {
        std::vector<std::string> inputs = files.scene_paths;
        if (!files.material_path.empty()) inputs.insert(inputs.begin(), files.material_path);
        const std::string target = (files.out / "manifest.json").string();
        if (std::string why = depfile_refusal(files.depfile, inputs, files.out); !why.empty()) {
            run.depfile_error = why;
            run.depfile_refused = true;
            return run;
        }
        std::string unnamed;
        if (!depfile_text(target, inputs, &unnamed)) {
            run.depfile_error = files.depfile + ": " + unnamed;
            run.depfile_refused = true;
            return run;
        }
        if (auto e = write_depfile(files.depfile, target, inputs)) {
            run.depfile_error = *e;
            return run;
        }
    }
    // Nothing changed and the output is intact: not even the material is loaded.
    if (auto done = build_up_to_date(request)) {
        run.summary = *done;
        return run;
    }
    if (!load_material_and_scenes(files.material_path, files.scene_paths, request.material,
                                  request.scenes, run.load_diagnostics))
        return run;
    run.summary = build_material_now(request); // checked above
    run.built = true;
    return run;
}

} // namespace watergen
