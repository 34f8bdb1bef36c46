// Compute dispatches on the headless device (HeadlessDevice::compute), the numeric harness:
// node functions compiled into a compute shader read input tuples from storage buffers (and
// textures) and write results to others; every storage buffer is read back after one dispatch.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "watergen/headless/texture_data.h"
#include "watergen/runtime/reflection.h"

namespace watergen {

struct ComputeJob {
    std::vector<uint32_t> spirv;
    Reflection reflection;
    // Initial contents of StorageBuffer bindings, by reflection binding name (the block
    // type name, e.g. "Inputs"). Entries no binding uses are ignored.
    std::map<std::string, std::vector<uint8_t>> buffers;
    // Sizes of StorageBuffer bindings the shader only writes (zero-filled before the
    // dispatch). A storage binding in neither map gets its reflected block_size, if nonzero.
    std::map<std::string, uint64_t> output_sizes;
    // Bytes of the UniformBuffer binding, if the shader has one.
    std::vector<uint8_t> uniforms;
    // Values of float specialization constants by constant_id; a constant with no entry keeps
    // the module's default.
    std::map<uint32_t, float> specialization;
    // SampledImage / CombinedImageSampler bindings by binding name, and their sampler (clamp to
    // edge, no mips).
    std::map<std::string, TextureData> textures;
    TextureFilter filter = TextureFilter::Linear;
    uint32_t group_count_x = 1;
    uint32_t group_count_y = 1;
    uint32_t group_count_z = 1;
};

struct ComputeOutput {
    // Contents of every StorageBuffer binding after the dispatch, by binding name.
    std::map<std::string, std::vector<uint8_t>> buffers;
    double pipeline_ms = 0; // CPU time of vkCreateComputePipelines
    double dispatch_ms = 0; // CPU wall time of the submit + wait (includes JIT)
};

} // namespace watergen
