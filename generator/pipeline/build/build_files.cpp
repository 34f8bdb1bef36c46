#include "watergen/pipeline/build/build_files.h"

#include "watergen/pipeline/output/depfile.h"
#include "watergen/pipeline/record/build_record.h"
#include "watergen/plan/binding_map_file.h"
#include "watergen/plan/scene_file.h"
#include "watergen/water/binding_profiles.h"

namespace watergen {

BuildFilesRun build_from_files(const BuildFilesRequest& files) {
    BuildFilesRun run;
    BuildRequest request;
    request.mode = files.mode;
    request.freeze = files.freeze;
    request.shard = files.shard;
    // Hashed before they are loaded: a file changed in between makes the record stale, never
    // wrong.
    const bool map_file = !files.bindings.empty() && !binding_profile(files.bindings);
    std::vector<std::string> scene_like = files.scene_paths;
    if (map_file) scene_like.push_back(files.bindings); // hashed with its name and bytes
    request.inputs_hash =
        build_inputs_hash(files.material_path, scene_like,
                          std::string(to_string(files.mode)) + (files.freeze ? " freeze" : "") +
                              " bindings " + (map_file ? "file" : files.bindings))
            .value_or("");
    request.out = files.out;
    request.options = files.options;
    // Written before the build: it depends on the inputs only, and a depfile that cannot be
    // written stops the build before anything else is.
    if (!files.depfile.empty()) {
        std::vector<std::string> inputs = files.scene_paths;
        if (!files.material_path.empty()) inputs.insert(inputs.begin(), files.material_path);
        if (map_file) inputs.push_back(files.bindings);
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
    std::optional<BindingMap> map = load_binding_map(
        files.bindings.empty() ? std::string("watergen") : files.bindings, run.load_diagnostics);
    if (!map) return run;
    request.options.bindings = &*map;
    run.summary = build_material_now(request); // checked above
    run.built = true;
    return run;
}

} // namespace watergen
