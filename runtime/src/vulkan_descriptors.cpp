// Descriptor set layouts from the union of the stages' Reflection bindings, and the
// buffers, textures and samplers a job supplies for them (matched by binding name).
#include "pipeline_state.h"
#include "vulkan_internal.h"
#include "watergen/runtime/variant_pipeline.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <utility>

namespace watergen::vk_detail {
namespace {

struct Merged {
    DescriptorBinding binding;
    VkShaderStageFlags stages = 0;
};

std::string where(const DescriptorBinding& b) {
    return fmt::format("{} '{}' (set {}, binding {})", to_string(b.kind), b.name, b.set, b.binding);
}

// A binding both stages declare must agree on name and kind; the layout then makes it
// visible to both stages.
std::map<std::pair<uint32_t, uint32_t>, Merged> merge(const std::vector<StageReflection>& stages) {
    std::map<std::pair<uint32_t, uint32_t>, Merged> merged;
    for (const StageReflection& s : stages) {
        for (const DescriptorBinding& b : s.reflection->bindings) {
            auto [it, inserted] = merged.try_emplace({b.set, b.binding}, Merged{b, s.stage});
            if (inserted) continue;
            Merged& m = it->second;
            if (m.binding.kind != b.kind || m.binding.name != b.name)
                throw RunnerError(fmt::format("stages disagree on set {} binding {}: {} vs {}",
                                              b.set, b.binding, where(m.binding), where(b)));
            m.stages |= s.stage;
            m.binding.block_size = std::max(m.binding.block_size, b.block_size);
        }
    }
    return merged;
}

VkSampler create_sampler(Scope& scope, TextureFilter filter) {
    Context& ctx = scope.ctx();
    if (filter == TextureFilter::Linear) {
        VkFormatProperties props{};
        vkGetPhysicalDeviceFormatProperties(ctx.physical, VK_FORMAT_R32G32B32A32_SFLOAT, &props);
        if (!(props.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT))
            throw RunnerError(fmt::format(
                "device '{}' cannot filter RGBA32F textures linearly; use nearest", ctx.info.name));
    }
    const VkFilter f = filter == TextureFilter::Linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
    const VkSamplerCreateInfo sci = vk_state::clamp_sampler_info(f);
    VkSampler sampler = VK_NULL_HANDLE;
    vk_check(vkCreateSampler(ctx.device, &sci, nullptr, &sampler), "vkCreateSampler");
    VkDevice device = ctx.device;
    scope.defer([device, sampler] { vkDestroySampler(device, sampler, nullptr); });
    return sampler;
}

Buffer uniform_buffer(Scope& scope, const DescriptorBinding& b, const DescriptorInputs& in) {
    if (!in.uniforms || in.uniforms->empty())
        throw RunnerError(
            fmt::format("{} is not supplied by the job (uniforms is empty)", where(b)));
    const size_t size = in.uniforms->size();
    if (size < b.block_size)
        throw RunnerError(
            fmt::format("{} needs {} bytes; the job supplies {}", where(b), b.block_size, size));
    if (size > scope.ctx().limits.maxUniformBufferRange)
        throw RunnerError(fmt::format("{}: {} bytes exceed maxUniformBufferRange {}", where(b),
                                      size, scope.ctx().limits.maxUniformBufferRange));
    Buffer buf = create_buffer(scope, size, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    write_buffer(scope.ctx(), buf, in.uniforms->data(), size);
    return buf;
}

Buffer storage_buffer(Scope& scope, const DescriptorBinding& b, const DescriptorInputs& in) {
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    if (in.storage) {
        if (auto it = in.storage->find(b.name); it != in.storage->end()) {
            if (it->second.empty())
                throw RunnerError(fmt::format("{}: the job's buffer is empty", where(b)));
            Buffer buf = create_buffer(scope, it->second.size(), usage);
            write_buffer(scope.ctx(), buf, it->second.data(), it->second.size());
            return buf;
        }
    }
    uint64_t size = 0;
    if (in.storage_sizes) {
        if (auto it = in.storage_sizes->find(b.name); it != in.storage_sizes->end())
            size = it->second;
    }
    if (size == 0) size = b.block_size; // fixed-size blocks need no size from the caller
    if (size == 0)
        throw RunnerError(
            fmt::format("{} is not supplied by the job (no contents or size)", where(b)));
    return create_buffer(scope, size, usage); // zero-filled by create_buffer
}

Image texture(Scope& scope, const DescriptorBinding& b, const DescriptorInputs& in) {
    const TextureData* data = nullptr;
    if (in.textures) {
        if (auto it = in.textures->find(b.name); it != in.textures->end()) data = &it->second;
    }
    if (!data) throw RunnerError(fmt::format("texture {} is not supplied by the job", where(b)));
    if (b.image_dim != "2D" && b.image_dim != "Cube" && !b.image_dim.empty())
        throw RunnerError(fmt::format("{}: image dimension '{}' is not supported (2D, Cube)",
                                      where(b), b.image_dim));
    return create_texture(scope, b.name, *data, b.image_dim == "Cube");
}

using MergedBindings = std::map<std::pair<uint32_t, uint32_t>, Merged>;

// Throws when the device or the job cannot serve the bindings.
void check_bindings(const Context& ctx, const MergedBindings& merged, uint32_t set_count) {
    if (set_count > ctx.limits.maxBoundDescriptorSets)
        throw RunnerError(fmt::format("shader uses descriptor set {}; the device binds at most {}",
                                      set_count - 1, ctx.limits.maxBoundDescriptorSets));

    // RenderJob / ComputeJob carry one block of uniform bytes: more than one uniform
    // buffer binding would be ambiguous.
    std::vector<std::string> uniform_names;
    for (const auto& [key, m] : merged)
        if (m.binding.kind == DescriptorKind::UniformBuffer)
            uniform_names.push_back(m.binding.name);
    if (uniform_names.size() > 1)
        throw RunnerError(fmt::format("shaders declare {} uniform blocks ({}); the job's uniforms "
                                      "bytes can feed only one",
                                      uniform_names.size(), fmt::join(uniform_names, ", ")));
}

// One layout per set number (gaps get empty ones), a pool sized for them, and the sets.
void allocate_sets(Scope& scope, const MergedBindings& merged, uint32_t set_count,
                   BoundDescriptors& out) {
    std::vector<std::vector<VkDescriptorSetLayoutBinding>> per_set(set_count);
    std::map<VkDescriptorType, uint32_t> type_counts;
    for (const auto& [key, m] : merged) {
        VkDescriptorSetLayoutBinding lb{};
        lb.binding = m.binding.binding;
        lb.descriptorType = descriptor_type(m.binding.kind);
        lb.descriptorCount = 1;
        lb.stageFlags = m.stages;
        per_set[key.first].push_back(lb);
        ++type_counts[lb.descriptorType];
    }

    VkDevice device = scope.ctx().device;
    for (const auto& bindings : per_set) {
        VkDescriptorSetLayoutCreateInfo lci{};
        lci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
        lci.bindingCount = static_cast<uint32_t>(bindings.size());
        lci.pBindings = bindings.data();
        VkDescriptorSetLayout layout = VK_NULL_HANDLE;
        vk_check(vkCreateDescriptorSetLayout(device, &lci, nullptr, &layout),
                 "vkCreateDescriptorSetLayout");
        scope.defer([device, layout] { vkDestroyDescriptorSetLayout(device, layout, nullptr); });
        out.layouts.push_back(layout);
    }

    std::vector<VkDescriptorPoolSize> sizes;
    for (const auto& [type, count] : type_counts)
        sizes.push_back({type, count});
    VkDescriptorPoolCreateInfo pci{};
    pci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pci.maxSets = set_count;
    pci.poolSizeCount = static_cast<uint32_t>(sizes.size());
    pci.pPoolSizes = sizes.data();
    VkDescriptorPool pool = VK_NULL_HANDLE;
    vk_check(vkCreateDescriptorPool(device, &pci, nullptr, &pool), "vkCreateDescriptorPool");
    scope.defer([device, pool] { vkDestroyDescriptorPool(device, pool, nullptr); });

    VkDescriptorSetAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    ai.descriptorPool = pool;
    ai.descriptorSetCount = set_count;
    ai.pSetLayouts = out.layouts.data();
    out.sets.resize(set_count);
    vk_check(vkAllocateDescriptorSets(device, &ai, out.sets.data()), "vkAllocateDescriptorSets");
}

// Creates every resource the bindings point at and writes it into the sets.
void write_descriptors(Scope& scope, const MergedBindings& merged, const DescriptorInputs& inputs,
                       BoundDescriptors& out) {
    // Infos are referenced by pointer from the writes: size the vectors up front so they
    // never reallocate.
    std::vector<VkDescriptorBufferInfo> buffer_infos;
    std::vector<VkDescriptorImageInfo> image_infos;
    buffer_infos.reserve(merged.size());
    image_infos.reserve(merged.size());
    std::vector<VkWriteDescriptorSet> writes;
    // Every Sampler / CombinedImageSampler binding gets the same settings, so one VkSampler
    // object serves them all.
    VkSampler sampler = VK_NULL_HANDLE;

    for (const auto& [key, m] : merged) {
        const DescriptorBinding& b = m.binding;
        VkWriteDescriptorSet w{};
        w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        w.dstSet = out.sets[b.set];
        w.dstBinding = b.binding;
        w.descriptorCount = 1;
        w.descriptorType = descriptor_type(b.kind);
        switch (b.kind) {
        case DescriptorKind::UniformBuffer: {
            Buffer buf = uniform_buffer(scope, b, inputs);
            buffer_infos.push_back({buf.buffer, 0, VK_WHOLE_SIZE});
            w.pBufferInfo = &buffer_infos.back();
            break;
        }
        case DescriptorKind::StorageBuffer: {
            Buffer buf = storage_buffer(scope, b, inputs);
            out.storage_buffers[b.name] = buf;
            buffer_infos.push_back({buf.buffer, 0, VK_WHOLE_SIZE});
            w.pBufferInfo = &buffer_infos.back();
            break;
        }
        case DescriptorKind::Sampler:
            if (!sampler) sampler = create_sampler(scope, inputs.filter);
            image_infos.push_back({sampler, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED});
            w.pImageInfo = &image_infos.back();
            break;
        case DescriptorKind::SampledImage:
        case DescriptorKind::CombinedImageSampler: {
            Image img = texture(scope, b, inputs);
            VkSampler s = VK_NULL_HANDLE;
            if (b.kind == DescriptorKind::CombinedImageSampler) {
                if (!sampler) sampler = create_sampler(scope, inputs.filter);
                s = sampler;
            }
            image_infos.push_back({s, img.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
            w.pImageInfo = &image_infos.back();
            break;
        }
        }
        writes.push_back(w);
    }
    vkUpdateDescriptorSets(scope.ctx().device, static_cast<uint32_t>(writes.size()), writes.data(),
                           0, nullptr);
}

} // namespace

BoundDescriptors bind_descriptors(Scope& scope, const std::vector<StageReflection>& stages,
                                  const DescriptorInputs& inputs) {
    const MergedBindings merged = merge(stages);
    BoundDescriptors out;
    if (merged.empty()) return out;
    const uint32_t set_count = merged.rbegin()->first.first + 1;
    check_bindings(scope.ctx(), merged, set_count);
    allocate_sets(scope, merged, set_count, out);
    write_descriptors(scope, merged, inputs, out);
    return out;
}

VkPipelineLayout create_pipeline_layout(Scope& scope, const BoundDescriptors& d) {
    VkPipelineLayoutCreateInfo lci{};
    lci.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    lci.setLayoutCount = static_cast<uint32_t>(d.layouts.size());
    lci.pSetLayouts = d.layouts.data();
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkDevice device = scope.ctx().device;
    vk_check(vkCreatePipelineLayout(device, &lci, nullptr, &layout), "vkCreatePipelineLayout");
    scope.defer([device, layout] { vkDestroyPipelineLayout(device, layout, nullptr); });
    return layout;
}

} // namespace watergen::vk_detail
