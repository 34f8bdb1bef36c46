// Descriptor sets and the buffers, textures and samplers the inputs supply for their bindings
// (matched by binding name); a compute stage's set layouts (see descriptors.h).
#include "descriptors.h"

#include "watergen/runtime/variant_pipeline.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace watergen::headless_detail {
namespace {

std::string where(const DescriptorBinding& b) {
    return fmt::format("{} '{}' (set {}, binding {})", to_string(b.kind), b.name, b.set, b.binding);
}

// Clamp to edge on every axis, one mip level.
VkSampler create_sampler(Scope& scope, TextureFilter filter) {
    Context& ctx = scope.ctx();
    if (filter == TextureFilter::Linear) {
        VkFormatProperties props{};
        vkGetPhysicalDeviceFormatProperties(ctx.physical, VK_FORMAT_R32G32B32A32_SFLOAT, &props);
        if (!(props.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT))
            throw DeviceError(fmt::format(
                "device '{}' cannot filter RGBA32F textures linearly; use nearest", ctx.info.name));
    }
    const VkFilter f = filter == TextureFilter::Linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
    VkSamplerCreateInfo sci{};
    sci.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
    sci.magFilter = f;
    sci.minFilter = f;
    sci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    sci.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    sci.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    sci.maxLod = 0.0f; // textures have one level
    sci.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
    VkSampler sampler = VK_NULL_HANDLE;
    check(vkCreateSampler(ctx.device, &sci, nullptr, &sampler), "vkCreateSampler");
    VkDevice device = ctx.device;
    scope.defer([device, sampler] { vkDestroySampler(device, sampler, nullptr); });
    return sampler;
}

Buffer uniform_buffer(Scope& scope, const DescriptorBinding& b, const DescriptorInputs& in) {
    const std::vector<uint8_t>* bytes = in.sole_uniforms;
    if (in.uniforms) {
        if (auto it = in.uniforms->find(b.name); it != in.uniforms->end()) bytes = &it->second;
    }
    if (!bytes || bytes->empty())
        throw DeviceError(
            fmt::format("{} is not supplied ({} bytes needed)", where(b), b.block_size));
    const size_t size = bytes->size();
    if (size < b.block_size)
        throw DeviceError(
            fmt::format("{} needs {} bytes; {} supplied", where(b), b.block_size, size));
    if (size > scope.ctx().limits.maxUniformBufferRange)
        throw DeviceError(fmt::format("{}: {} bytes exceed maxUniformBufferRange {}", where(b),
                                      size, scope.ctx().limits.maxUniformBufferRange));
    return upload_buffer(scope, bytes->data(), size, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
}

Buffer storage_buffer(Scope& scope, const DescriptorBinding& b, const DescriptorInputs& in) {
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    if (in.storage) {
        if (auto it = in.storage->find(b.name); it != in.storage->end()) {
            if (it->second.empty())
                throw DeviceError(fmt::format("{}: the buffer supplied is empty", where(b)));
            return upload_buffer(scope, it->second.data(), it->second.size(), usage);
        }
    }
    uint64_t size = 0;
    if (in.storage_sizes) {
        if (auto it = in.storage_sizes->find(b.name); it != in.storage_sizes->end())
            size = it->second;
    }
    if (size == 0) size = b.block_size; // fixed-size blocks need no size from the caller
    if (size == 0)
        throw DeviceError(fmt::format("{} is not supplied (no contents or size)", where(b)));
    return create_buffer(scope, size, usage); // zero-filled by create_buffer
}

Image texture(Scope& scope, const DescriptorBinding& b, const DescriptorInputs& in) {
    const TextureData* data = nullptr;
    if (in.textures) {
        if (auto it = in.textures->find(b.name); it != in.textures->end()) data = &it->second;
    }
    if (!data) throw DeviceError(fmt::format("texture {} is not supplied", where(b)));
    if (b.image_dim != "2D" && b.image_dim != "Cube" && !b.image_dim.empty())
        throw DeviceError(fmt::format("{}: image dimension '{}' is not supported (2D, Cube)",
                                      where(b), b.image_dim));
    return create_texture(scope, b.name, *data, b.image_dim == "Cube");
}

// One block of bytes can feed only one uniform binding, or the push-constant block.
void check_sole_uniform(const SetBindings& bindings, const DescriptorBinding* push) {
    std::vector<std::string> names;
    for (const auto& set : bindings)
        for (const DescriptorBinding& b : set)
            if (b.kind == DescriptorKind::UniformBuffer) names.push_back(b.name);
    if (push && !names.empty())
        throw DeviceError(fmt::format("shaders declare uniform block(s) {} and push-constant "
                                      "block '{}'; the job's uniforms bytes can feed only one",
                                      fmt::join(names, ", "), push->name));
    if (names.size() > 1)
        throw DeviceError(fmt::format("shaders declare {} uniform blocks ({}); the job's uniforms "
                                      "bytes can feed only one",
                                      names.size(), fmt::join(names, ", ")));
}

// A pool for one set per layout, and the sets.
std::vector<VkDescriptorSet> allocate_sets(Scope& scope,
                                           const std::vector<VkDescriptorSetLayout>& layouts,
                                           const SetBindings& bindings,
                                           const std::vector<VkDescriptorPoolSize>* counts) {
    std::vector<VkDescriptorPoolSize> sizes;
    if (counts) {
        sizes = *counts;
    } else {
        std::vector<DescriptorKind> kinds;
        for (const auto& set : bindings)
            for (const DescriptorBinding& b : set)
                kinds.push_back(b.kind);
        sizes = pool_sizes_of(kinds);
    }
    VkDevice device = scope.ctx().device;
    VkDescriptorPoolCreateInfo pci{};
    pci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pci.maxSets = static_cast<uint32_t>(layouts.size());
    pci.poolSizeCount = static_cast<uint32_t>(sizes.size());
    pci.pPoolSizes = sizes.data();
    VkDescriptorPool pool = VK_NULL_HANDLE;
    check(vkCreateDescriptorPool(device, &pci, nullptr, &pool), "vkCreateDescriptorPool");
    scope.defer([device, pool] { vkDestroyDescriptorPool(device, pool, nullptr); });

    VkDescriptorSetAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    ai.descriptorPool = pool;
    ai.descriptorSetCount = static_cast<uint32_t>(layouts.size());
    ai.pSetLayouts = layouts.data();
    std::vector<VkDescriptorSet> sets(layouts.size());
    check(vkAllocateDescriptorSets(device, &ai, sets.data()), "vkAllocateDescriptorSets");
    return sets;
}

} // namespace

BoundDescriptors bind_descriptors(Scope& scope, const std::vector<VkDescriptorSetLayout>& layouts,
                                  const SetBindings& bindings, const DescriptorInputs& inputs,
                                  const std::vector<VkDescriptorPoolSize>* pool) {
    BoundDescriptors out;
    if (layouts.empty()) return out;
    const Context& ctx = scope.ctx();
    if (layouts.size() > ctx.limits.maxBoundDescriptorSets)
        throw DeviceError(fmt::format("shader uses descriptor set {}; the device binds at most {}",
                                      layouts.size() - 1, ctx.limits.maxBoundDescriptorSets));
    if (inputs.sole_uniforms) check_sole_uniform(bindings, inputs.push_constant);
    out.sets = allocate_sets(scope, layouts, bindings, pool);

    // Infos are referenced by pointer from the writes: size the vectors up front so they
    // never reallocate.
    size_t count = 0;
    for (const auto& set : bindings)
        count += set.size();
    std::vector<VkDescriptorBufferInfo> buffer_infos;
    std::vector<VkDescriptorImageInfo> image_infos;
    buffer_infos.reserve(count);
    image_infos.reserve(count);
    std::vector<VkWriteDescriptorSet> writes;
    // Every Sampler / CombinedImageSampler binding gets the same settings, so one VkSampler
    // object serves them all.
    VkSampler sampler = VK_NULL_HANDLE;
    for (const auto& set : bindings)
        for (const DescriptorBinding& b : set) {
            VkWriteDescriptorSet w{};
            w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
            w.dstSet = out.sets[b.set];
            w.dstBinding = b.binding;
            w.descriptorCount = 1;
            w.descriptorType = descriptor_type(b.kind);
            if (b.kind == DescriptorKind::UniformBuffer ||
                b.kind == DescriptorKind::StorageBuffer) {
                const bool uniform = b.kind == DescriptorKind::UniformBuffer;
                const Buffer buf =
                    uniform ? uniform_buffer(scope, b, inputs) : storage_buffer(scope, b, inputs);
                if (!uniform) out.storage_buffers[b.name] = buf;
                buffer_infos.push_back({buf.buffer, 0, VK_WHOLE_SIZE});
                w.pBufferInfo = &buffer_infos.back();
            } else {
                VkDescriptorImageInfo info{VK_NULL_HANDLE, VK_NULL_HANDLE,
                                           VK_IMAGE_LAYOUT_UNDEFINED};
                if (b.kind != DescriptorKind::SampledImage) {
                    if (!sampler) sampler = create_sampler(scope, inputs.filter);
                    info.sampler = sampler;
                }
                if (b.kind != DescriptorKind::Sampler) {
                    info.imageView = texture(scope, b, inputs).view;
                    info.imageLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
                }
                image_infos.push_back(info);
                w.pImageInfo = &image_infos.back();
            }
            writes.push_back(w);
        }
    vkUpdateDescriptorSets(ctx.device, static_cast<uint32_t>(writes.size()), writes.data(), 0,
                           nullptr);
    return out;
}

std::vector<uint8_t> push_constant_bytes(const Context& ctx, const DescriptorBinding& block,
                                         uint32_t range, const SetBindings& bindings,
                                         const DescriptorInputs& in) {
    const std::string what = fmt::format("push-constant block '{}'", block.name);
    if (range > ctx.limits.maxPushConstantsSize)
        throw DeviceError(fmt::format("{}: a range of {} bytes exceeds maxPushConstantsSize {}",
                                      what, range, ctx.limits.maxPushConstantsSize));
    const std::vector<uint8_t>* bytes = in.sole_uniforms;
    if (bytes) check_sole_uniform(bindings, &block);
    if (in.uniforms) {
        if (auto it = in.uniforms->find(block.name); it != in.uniforms->end()) bytes = &it->second;
    }
    if (!bytes || bytes->empty())
        throw DeviceError(
            fmt::format("{} is not supplied ({} bytes needed)", what, block.block_size));
    if (bytes->size() < block.block_size)
        throw DeviceError(
            fmt::format("{} needs {} bytes; {} supplied", what, block.block_size, bytes->size()));
    // size_t: a block_size near 2^32 must not wrap; the range check above bounds it in practice.
    const size_t pushed = (size_t(block.block_size) + 3) / 4 * 4;
    if (pushed > range)
        throw DeviceError(fmt::format("{} of {} bytes pushes {}; the layout's push-constant "
                                      "range has {}",
                                      what, block.block_size, pushed, range));
    // Zero padding past block_size; a copy so the recorded draw never points at the caller's.
    std::vector<uint8_t> out(pushed, 0);
    std::copy_n(bytes->begin(), std::min(pushed, bytes->size()), out.begin());
    return out;
}

SetBindings stage_bindings(const Reflection& reflection) {
    SetBindings out;
    for (const DescriptorBinding& b : reflection.bindings) {
        if (b.set >= out.size()) out.resize(b.set + 1);
        out[b.set].push_back(b);
    }
    return out;
}

std::vector<VkDescriptorSetLayout> create_set_layouts(Scope& scope, const SetBindings& bindings,
                                                      VkShaderStageFlags stage) {
    VkDevice device = scope.ctx().device;
    std::vector<VkDescriptorSetLayout> layouts;
    for (const auto& set : bindings) {
        std::vector<VkDescriptorSetLayoutBinding> entries;
        for (const DescriptorBinding& b : set)
            entries.push_back({b.binding, descriptor_type(b.kind), 1, stage, nullptr});
        VkDescriptorSetLayoutCreateInfo lci{};
        lci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
        lci.bindingCount = static_cast<uint32_t>(entries.size());
        lci.pBindings = entries.data();
        VkDescriptorSetLayout layout = VK_NULL_HANDLE;
        check(vkCreateDescriptorSetLayout(device, &lci, nullptr, &layout),
              "vkCreateDescriptorSetLayout");
        scope.defer([device, layout] { vkDestroyDescriptorSetLayout(device, layout, nullptr); });
        layouts.push_back(layout);
    }
    return layouts;
}

VkPipelineLayout create_pipeline_layout(Scope& scope,
                                        const std::vector<VkDescriptorSetLayout>& layouts) {
    VkPipelineLayoutCreateInfo lci{};
    lci.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    lci.setLayoutCount = static_cast<uint32_t>(layouts.size());
    lci.pSetLayouts = layouts.data();
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkDevice device = scope.ctx().device;
    check(vkCreatePipelineLayout(device, &lci, nullptr, &layout), "vkCreatePipelineLayout");
    scope.defer([device, layout] { vkDestroyPipelineLayout(device, layout, nullptr); });
    return layout;
}

} // namespace watergen::headless_detail
