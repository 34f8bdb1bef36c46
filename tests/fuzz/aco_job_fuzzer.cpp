// The ACO worker's job.json (eval/measure/aco_job.cpp): every input either yields a job or an
// error; a job it yields holds only what a driver can be given (a colour format, at most 16
// vertex attributes of 1 to 4 floats, patches of at most 32 points, finite constants).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "watergen/eval/measure/aco_job.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace watergen;
    std::string error;
    const auto job =
        parse_aco_job(std::string_view(reinterpret_cast<const char*>(data), size), &error);
    if (!job) {
        if (error.empty()) std::abort(); // a refusal must say why
        return 0;
    }
    for (const AcoJobPipeline& p : job->pipelines) {
        if (!is_colour_format(p.format)) std::abort();
        for (const auto& [id, value] : p.specialization)
            if (!std::isfinite(value)) std::abort();
        if (!p.geometry) continue;
        if (p.geometry->attribute_sizes.size() > kMaxVertexAttributes ||
            p.geometry->patch_control_points > kMaxPatchControlPoints)
            std::abort();
        for (uint32_t n : p.geometry->attribute_sizes)
            if (n < 1 || n > 4) std::abort();
    }
    return 0;
}
