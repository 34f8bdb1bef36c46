// The job file of the ACO worker (aco_worker.h), DIR/job.json, as the worker reads it: every
// value checked before a driver sees it. A job directory is a file protocol; whatever wrote it,
// the worker refuses what is wrong with a message and never crashes on it (the fuzz target
// tests/fuzz/aco_job_fuzzer.cpp holds it to that).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "watergen/runtime/variant_pipeline.h"

namespace watergen {

constexpr size_t kMaxAcoJobPipelines = size_t(1) << 20;

// One pipeline's entry (its SPIR-V and reflection are files beside job.json).
struct AcoJobPipeline {
    std::string name;
    std::map<uint32_t, float> specialization;
    VkFormat format = VK_FORMAT_R16G16B16A16_SFLOAT; // a colour format (is_colour_format)
    bool tessellated = false;
    // At most kMaxVertexAttributes attributes of 1 to 4 floats, patches of at most
    // kMaxPatchControlPoints.
    std::optional<PipelineGeometry> geometry;
};
struct AcoJob {
    bool disassembly = true;
    std::vector<AcoJobPipeline> pipelines;
};

// The job in `text`; nullopt and *error saying which pipeline and key is wrong.
std::optional<AcoJob> parse_aco_job(std::string_view text, std::string* error);

} // namespace watergen
