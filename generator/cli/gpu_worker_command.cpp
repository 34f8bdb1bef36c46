// `watergen gpu-worker DIR`: hidden; the child process in which RADV's null device compiles a
// job's pipelines (aco_worker.h). Run only by watergen itself, with the environment set.
#include "commands.h"
#include "watergen/eval/measure/aco_worker.h"

namespace watergen::cli {

Runner add_gpu_worker_command(CLI::App& app) {
    auto dir = std::make_shared<std::string>();
    app.add_option("dir", *dir, "the job directory")->required();
    return [dir]() { return run_aco_worker(*dir); };
}

} // namespace watergen::cli
