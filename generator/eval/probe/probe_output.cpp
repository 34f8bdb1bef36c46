#include "watergen/eval/probe/probe_output.h"

#include "watergen/pipeline/output/output_writer.h"

namespace watergen {

ProbeOutput write_probe(VulkanRunner& runner, const ProbeInputs& inputs, Language language,
                        bool strict_half, const std::filesystem::path& out) {
    ProbeOutput o;
    o.run = run_probe(runner, inputs.graph, language, inputs.tuples, inputs.params,
                      probe_scene_textures(), EmitOptions{strict_half});
    if (!o.run.ok()) {
        o.error = o.run.error;
        o.status = RunStatus::Failed;
        return o;
    }
    if (auto e = write_file_atomically(out, probe_results_csv(o.run, inputs.tuples))) {
        o.error = *e;
        o.status = RunStatus::Failed;
        return o;
    }
    o.summary = summarize_probe(o.run);
    return o;
}

} // namespace watergen
