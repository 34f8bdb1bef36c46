// Descriptor sets of a draw or dispatch: the pool, the sets, and the buffers, textures and
// samplers the inputs supply for their bindings (matched by binding name); the set layouts of a
// compute stage (a draw's come from its VariantPipeline). Not installed.
#pragma once

#include "resources.h"
#include "watergen/runtime/reflection.h"

#include <map>
#include <string>
#include <vector>

namespace watergen::headless_detail {

// What a draw or dispatch feeds into its bindings, by binding name; null maps: none of that kind.
struct DescriptorInputs {
    const std::map<std::string, std::vector<uint8_t>>* uniforms = nullptr;
    // The bytes of the one uniform block, whatever its name (a job of the test runner carries
    // one block); more than one uniform binding is then an error. In place of `uniforms`.
    // They feed the pipeline's push-constant block instead when it has one (push_constant).
    const std::vector<uint8_t>* sole_uniforms = nullptr;
    // The pipeline's push-constant block (VariantPipeline::push_constant()), if any: with
    // sole_uniforms, a uniform binding besides it is an error (one block of bytes feeds one).
    const DescriptorBinding* push_constant = nullptr;
    const std::map<std::string, TextureData>* textures = nullptr;
    TextureFilter filter = TextureFilter::Nearest;
    const std::map<std::string, std::vector<uint8_t>>* storage = nullptr;
    const std::map<std::string, uint64_t>* storage_sizes = nullptr;
};

// The bindings of each set number (index = set; a gap holds none).
using SetBindings = std::vector<std::vector<DescriptorBinding>>;

struct BoundDescriptors {
    std::vector<VkDescriptorSet> sets;             // one per layout
    std::map<std::string, Buffer> storage_buffers; // by binding name, for readback
};

// Allocates one set per layout and writes every binding from `inputs`; throws naming the
// binding an input is missing for. `pool`: the descriptor counts the layouts hold, when they
// hold more than `bindings` (a build's shared layout, of which a pipeline reads some slots).
BoundDescriptors bind_descriptors(Scope& scope, const std::vector<VkDescriptorSetLayout>& layouts,
                                  const SetBindings& bindings, const DescriptorInputs& inputs,
                                  const std::vector<VkDescriptorPoolSize>* pool = nullptr);

// The bytes vkCmdPushConstants records for `block` from `inputs` (by its name, else
// sole_uniforms): its block_size rounded up to 4 (UniformWriter::pack() pads to 16; the rest
// may be past the range). Throws naming the block when none are supplied, fewer than its
// block_size, sole_uniforms would also feed a uniform binding of `bindings`, or `range` (the
// layout's push-constant bytes) exceeds the device's maxPushConstantsSize.
std::vector<uint8_t> push_constant_bytes(const Context& ctx, const DescriptorBinding& block,
                                         uint32_t range, const SetBindings& bindings,
                                         const DescriptorInputs& inputs);

// One stage's bindings by set, and their layouts visible to `stage` (gaps get empty ones).
SetBindings stage_bindings(const Reflection& reflection);
std::vector<VkDescriptorSetLayout> create_set_layouts(Scope& scope, const SetBindings& bindings,
                                                      VkShaderStageFlags stage);
VkPipelineLayout create_pipeline_layout(Scope& scope,
                                        const std::vector<VkDescriptorSetLayout>& layouts);

} // namespace watergen::headless_detail
