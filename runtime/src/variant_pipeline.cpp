// Descriptor set layouts, pipeline layout and graphics pipeline from reflection; the pipeline
// cache file.
#include "watergen/runtime/variant_pipeline.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <tuple>
#include <unistd.h>

#include "pipeline_state.h"
#include "watergen/runtime/spirv_check.h"

namespace watergen {

namespace fs = std::filesystem;

namespace {

std::string failed(const char* call, VkResult r) {
    return std::string(call) + " failed: VkResult " + std::to_string(static_cast<int>(r));
}

VkShaderModule make_module(VkDevice device, const std::vector<uint32_t>& spirv, const char* stage,
                           std::string* error) {
    VkShaderModuleCreateInfo ci{};
    ci.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    ci.codeSize = spirv.size() * sizeof(uint32_t);
    ci.pCode = spirv.data();
    VkShaderModule m = VK_NULL_HANDLE;
    if (VkResult r = vkCreateShaderModule(device, &ci, nullptr, &m); r != VK_SUCCESS) {
        *error = std::string(stage) + " stage: " + failed("vkCreateShaderModule", r);
        return VK_NULL_HANDLE;
    }
    return m;
}

// One stage of the pipeline: its module, reflection and stage.
struct StageInput {
    const std::vector<uint32_t>* spirv;
    const Reflection* reflection;
    ShaderStage stage;
    VkShaderStageFlagBits flag;
};

// The stages `d` names, in pipeline order (the tessellation stages when given).
std::vector<StageInput> stages_of(const VariantPipelineDesc& d) {
    std::vector<StageInput> out = {
        {d.vertex_spirv, d.vertex_reflection, ShaderStage::Vertex, VK_SHADER_STAGE_VERTEX_BIT}};
    if (d.tess_control_spirv || d.tess_evaluation_spirv) {
        out.push_back({d.tess_control_spirv, d.tess_control_reflection, ShaderStage::TessControl,
                       VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT});
        out.push_back({d.tess_evaluation_spirv, d.tess_evaluation_reflection,
                       ShaderStage::TessEvaluation, VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT});
    }
    out.push_back({d.fragment_spirv, d.fragment_reflection, ShaderStage::Fragment,
                   VK_SHADER_STAGE_FRAGMENT_BIT});
    return out;
}

} // namespace

VkDescriptorType descriptor_type(DescriptorKind kind) {
    switch (kind) {
    case DescriptorKind::UniformBuffer:
        return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case DescriptorKind::StorageBuffer:
        return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case DescriptorKind::SampledImage:
        return VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    case DescriptorKind::Sampler:
        return VK_DESCRIPTOR_TYPE_SAMPLER;
    case DescriptorKind::CombinedImageSampler:
        return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    case DescriptorKind::PushConstant:
        // No descriptor at all: push-constant blocks are kept out of set layouts and pool sizes
        // (Reflection::push_constant, BindingLayout); this only keeps the switch whole.
        return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    }
    return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
}

VariantPipeline::VariantPipeline(VariantPipeline&& o) noexcept {
    *this = std::move(o);
}

VariantPipeline& VariantPipeline::operator=(VariantPipeline&& o) noexcept {
    if (this == &o) return *this;
    destroy();
    device_ = o.device_;
    set_layouts_ = std::move(o.set_layouts_);
    bindings_ = std::move(o.bindings_);
    layout_ = o.layout_;
    shared_ = o.shared_;
    pipeline_ = o.pipeline_;
    push_block_ = std::move(o.push_block_);
    push_range_ = o.push_range_;
    o.set_layouts_.clear();
    o.layout_ = VK_NULL_HANDLE;
    o.pipeline_ = VK_NULL_HANDLE;
    return *this;
}

VariantPipeline::~VariantPipeline() {
    destroy();
}

void VariantPipeline::destroy() {
    if (!device_) return;
    if (pipeline_) vkDestroyPipeline(device_, pipeline_, nullptr);
    if (layout_) vkDestroyPipelineLayout(device_, layout_, nullptr);
    for (VkDescriptorSetLayout l : set_layouts_)
        vkDestroyDescriptorSetLayout(device_, l, nullptr);
    set_layouts_.clear();
    pipeline_ = VK_NULL_HANDLE;
    layout_ = VK_NULL_HANDLE;
}

std::vector<VkDescriptorPoolSize> pool_sizes_of(const std::vector<DescriptorKind>& kinds,
                                                uint32_t copies) {
    std::map<VkDescriptorType, uint32_t> counts;
    for (DescriptorKind k : kinds)
        counts[descriptor_type(k)] += copies;
    std::vector<VkDescriptorPoolSize> sizes;
    for (const auto& [type, n] : counts)
        sizes.push_back({type, n});
    return sizes;
}

std::vector<VkDescriptorPoolSize> VariantPipeline::pool_sizes(uint32_t copies) const {
    if (shared_) return shared_->pool_sizes(copies);
    std::vector<DescriptorKind> kinds;
    for (const auto& set : bindings_)
        for (const DescriptorBinding& b : set)
            kinds.push_back(b.kind);
    return pool_sizes_of(kinds, copies);
}

bool VariantPipeline::create_own_layout(VkDevice device, const StageUnion& all, uint32_t sets,
                                        std::string* error) {
    bindings_.resize(sets);
    std::vector<std::vector<VkDescriptorSetLayoutBinding>> layout_bindings(sets);
    for (const auto& [key, b] : all) {
        bindings_[key.first].push_back(b.first);
        layout_bindings[key.first].push_back(
            {key.second, descriptor_type(b.first.kind), 1, b.second, nullptr});
    }
    for (uint32_t s = 0; s < sets; ++s) {
        VkDescriptorSetLayoutCreateInfo ci{};
        ci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
        ci.bindingCount = static_cast<uint32_t>(layout_bindings[s].size());
        ci.pBindings = layout_bindings[s].data();
        VkDescriptorSetLayout l = VK_NULL_HANDLE;
        if (VkResult r = vkCreateDescriptorSetLayout(device, &ci, nullptr, &l); r != VK_SUCCESS) {
            *error = failed("vkCreateDescriptorSetLayout", r);
            return false;
        }
        set_layouts_.push_back(l);
    }
    VkPipelineLayoutCreateInfo lci{};
    lci.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    lci.setLayoutCount = sets;
    lci.pSetLayouts = set_layouts_.data();
    lci.pushConstantRangeCount = push_range_.size ? 1 : 0;
    lci.pPushConstantRanges = push_range_.size ? &push_range_ : nullptr;
    if (VkResult r = vkCreatePipelineLayout(device, &lci, nullptr, &layout_); r != VK_SUCCESS) {
        *error = failed("vkCreatePipelineLayout", r);
        return false;
    }
    return true;
}

bool VariantPipeline::union_push_constants(const VariantPipelineDesc& d, std::string* error) {
    VkShaderStageFlags stages = 0;
    ShaderStage first = ShaderStage::Vertex; // the stage push_block_ was first seen in
    for (const StageInput& in : stages_of(d)) {
        if (!in.reflection->push_constant) continue;
        const DescriptorBinding& b = *in.reflection->push_constant;
        if (!push_block_) first = in.stage;
        // One range at offset 0 serves one block: two blocks would need two ranges and a
        // layout of offsets neither stage states.
        if (push_block_ && push_block_->name != b.name) {
            *error = "the push-constant block is '" + push_block_->name + "' in the " +
                     to_string(first) + " stage and '" + b.name + "' in the " +
                     to_string(in.stage) + " stage; expected one block";
            return false;
        }
        // The larger block covers both stages' members (the fragment's on a tie: the stage
        // UniformWriter::pack() reads).
        if (!push_block_ || b.block_size >= push_block_->block_size) push_block_ = b;
        stages |= static_cast<VkShaderStageFlags>(in.flag);
    }
    if (d.layout) {
        // The map's range, whether or not these stages read it; check() saw the block fits.
        if (const VkPushConstantRange* range = d.layout->push_constant_range())
            push_range_ = *range;
        return true;
    }
    if (!push_block_) return true;
    const std::string what = "push-constant block '" + push_block_->name + "' of " +
                             std::to_string(push_block_->block_size) + " bytes";
    // size_t: a block_size near 2^32 must not wrap to a small range.
    const size_t size = (size_t(push_block_->block_size) + 3) / 4 * 4;
    if (size == 0) {
        *error = what + "; expected a block of some bytes";
        return false;
    }
    if (size > d.max_push_constants_size) {
        *error = what + " exceeds the device's maxPushConstantsSize " +
                 std::to_string(d.max_push_constants_size);
        return false;
    }
    push_range_ = {stages, 0, static_cast<uint32_t>(size)};
    return true;
}

std::optional<VariantPipeline>
VariantPipeline::create(VkDevice device, const VariantPipelineDesc& d, std::string* error) {
    return create(device, d, PipelineGeometry{}, error);
}

std::optional<VariantPipeline> VariantPipeline::create(VkDevice device,
                                                       const VariantPipelineDesc& d,
                                                       const PipelineGeometry& geometry,
                                                       std::string* error) {
    if (!d.vertex_spirv || !d.fragment_spirv || !d.vertex_reflection || !d.fragment_reflection ||
        !d.render_pass) {
        *error = "VariantPipelineDesc: expected both stages' SPIR-V and reflection and a render "
                 "pass";
        return std::nullopt;
    }
    const bool tessellated = d.tess_control_spirv || d.tess_evaluation_spirv ||
                             d.tess_control_reflection || d.tess_evaluation_reflection;
    if (tessellated && (!d.tess_control_spirv || !d.tess_evaluation_spirv ||
                        !d.tess_control_reflection || !d.tess_evaluation_reflection)) {
        *error = "VariantPipelineDesc: expected both tessellation stages' SPIR-V and reflection, "
                 "or neither";
        return std::nullopt;
    }
    // A BindingLayout's bindings and range are visible to the vertex and fragment stages only.
    if (tessellated && d.layout) {
        *error = "VariantPipelineDesc: tessellation stages with a shared BindingLayout, whose "
                 "bindings the vertex and fragment stages alone see; expected a layout of the "
                 "pipeline's own (layout = null)";
        return std::nullopt;
    }
    // Tessellation stages read patches, and patches go nowhere else.
    if (tessellated != (geometry.patch_control_points > 0)) {
        *error = tessellated ? "PipelineGeometry: tessellation stages need patches; expected "
                               "patch_control_points > 0"
                             : "PipelineGeometry: patches of " +
                                   std::to_string(geometry.patch_control_points) +
                                   " control points need tessellation stages";
        return std::nullopt;
    }
    const std::vector<StageInput> inputs = stages_of(d);
    if (geometry.attribute_sizes.size() > kMaxVertexAttributes ||
        geometry.patch_control_points > kMaxPatchControlPoints) {
        *error = "PipelineGeometry: " + std::to_string(geometry.attribute_sizes.size()) +
                 " vertex attributes, patches of " + std::to_string(geometry.patch_control_points) +
                 " control points; expected at "
                 "most " +
                 std::to_string(kMaxVertexAttributes) + " and " +
                 std::to_string(kMaxPatchControlPoints) + " (what every Vulkan device takes)";
        return std::nullopt;
    }
    for (uint32_t floats : geometry.attribute_sizes)
        if (floats < 1 || floats > 4) {
            *error = "PipelineGeometry: a vertex attribute of " + std::to_string(floats) +
                     " floats; expected 1 to 4";
            return std::nullopt;
        }
    VariantPipeline p;
    // The driver trusts the modules: a vertex module in the fragment slot crashed lavapipe.
    for (const auto& [words, r, stage, flag] : inputs) {
        std::string why;
        if (!check_spirv(*words, stage, r->entry_point.empty() ? "main" : r->entry_point, &why)) {
            *error = std::string(to_string(stage)) + " stage: SPIR-V " + why;
            return std::nullopt;
        }
        // One descriptor set layout per set number up to the largest: bounded as a reflection
        // file's are (reflection.cpp), whoever made this one.
        for (const DescriptorBinding& b : r->bindings) {
            if (b.kind == DescriptorKind::PushConstant) {
                *error = std::string(to_string(stage)) + " stage: push-constant block '" + b.name +
                         "' among the descriptor bindings; expected it as the reflection's "
                         "push_constant";
                return std::nullopt;
            }
            if (b.set >= kMaxDescriptorSets) {
                *error = std::string(to_string(stage)) + " stage: binding '" + b.name +
                         "' in set " + std::to_string(b.set) + "; expected a set below " +
                         std::to_string(kMaxDescriptorSets);
                return std::nullopt;
            }
        }
    }
    p.device_ = device;
    // Union of the stages' bindings by (set, binding), stage flags or-ed together.
    StageUnion all;
    for (const StageInput& in : inputs)
        for (const DescriptorBinding& b : in.reflection->bindings) {
            auto [it, fresh] = all.try_emplace({b.set, b.binding}, b, 0);
            DescriptorBinding& seen = it->second.first;
            if (!fresh && (seen.kind != b.kind || seen.name != b.name)) {
                *error = "binding " + std::to_string(b.binding) + " of set " +
                         std::to_string(b.set) + " is " + to_string(seen.kind) + " '" + seen.name +
                         "' in one stage and " + to_string(b.kind) + " '" + b.name +
                         "' in the other";
                return std::nullopt;
            }
            // A block both stages declare needs the larger of their sizes.
            seen.block_size = std::max(seen.block_size, b.block_size);
            it->second.second |= static_cast<VkShaderStageFlags>(in.flag);
        }
    uint32_t sets = 0;
    for (const auto& [key, b] : all)
        sets = std::max(sets, key.first + 1);
    if (!p.union_push_constants(d, error)) return std::nullopt;
    if (d.layout) {
        for (const StageInput& in : inputs)
            if (std::string off = d.layout->check(*in.reflection); !off.empty()) {
                *error = off;
                return std::nullopt;
            }
        p.shared_ = d.layout;
        p.bindings_.resize(d.layout->set_layouts().size());
        for (const auto& [key, b] : all)
            p.bindings_[key.first].push_back(b.first);
    } else {
        if (!p.create_own_layout(device, all, sets, error)) return std::nullopt;
    }

    std::vector<VkSpecializationMapEntry> entries;
    std::vector<float> data;
    for (const auto& [id, value] : d.specialization) {
        entries.push_back({id, static_cast<uint32_t>(data.size() * sizeof(float)), sizeof(float)});
        data.push_back(value);
    }
    VkSpecializationInfo spec{static_cast<uint32_t>(entries.size()), entries.data(),
                              data.size() * sizeof(float), data.data()};
    std::vector<VkShaderModule> modules;
    auto destroy_modules = [&] {
        for (VkShaderModule m : modules)
            vkDestroyShaderModule(device, m, nullptr);
    };
    std::vector<VkPipelineShaderStageCreateInfo> stages(inputs.size());
    for (size_t i = 0; i < inputs.size(); ++i) {
        const VkShaderModule m =
            make_module(device, *inputs[i].spirv, to_string(inputs[i].stage), error);
        if (!m) {
            destroy_modules();
            return std::nullopt;
        }
        modules.push_back(m);
        const Reflection& r = *inputs[i].reflection;
        stages[i].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
        stages[i].stage = inputs[i].flag;
        stages[i].module = m;
        stages[i].pName = r.entry_point.empty() ? "main" : r.entry_point.c_str();
        stages[i].pSpecializationInfo = entries.empty() ? nullptr : &spec;
    }
    const vk_state::VertexInput vertex_input(geometry.attribute_sizes);
    vk_state::FixedFunction fixed;
    if (geometry.points) fixed.points();
    if (geometry.patch_control_points) fixed.patches(geometry.patch_control_points);
    if (geometry.cull_back_faces) fixed.raster.cullMode = VK_CULL_MODE_BACK_BIT;
    if (geometry.additive_blend) fixed.additive_blend();
    VkPipelineViewportStateCreateInfo viewport{};
    viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    const VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{};
    dynamic.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamic_states;

    VkGraphicsPipelineCreateInfo gci{};
    fixed.apply(gci);
    gci.stageCount = static_cast<uint32_t>(stages.size());
    gci.pStages = stages.data();
    gci.pVertexInputState = &vertex_input.info;
    gci.pViewportState = &viewport;
    gci.pDynamicState = &dynamic;
    gci.layout = p.layout();
    gci.renderPass = d.render_pass;
    gci.subpass = d.subpass;
    gci.flags = d.flags;
    const VkResult r = vkCreateGraphicsPipelines(device, d.cache, 1, &gci, nullptr, &p.pipeline_);
    destroy_modules();
    if (r != VK_SUCCESS) {
        p.pipeline_ = VK_NULL_HANDLE;
        *error = failed("vkCreateGraphicsPipelines", r);
        return std::nullopt;
    }
    return p;
}

std::optional<PipelineCacheFile> load_pipeline_cache(VkPhysicalDevice physical, VkDevice device,
                                                     const fs::path& file, std::string* error) {
    PipelineCacheFile out;
    std::string data;
    std::error_code ec;
    if (fs::is_regular_file(file, ec)) {
        std::ifstream in(file, std::ios::binary);
        data.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        // The header (VkPipelineCacheHeaderVersionOne): length, version, vendor, device, UUID.
        VkPhysicalDeviceProperties props{};
        vkGetPhysicalDeviceProperties(physical, &props);
        VkPipelineCacheHeaderVersionOne header{};
        if (data.size() < sizeof(header)) {
            out.note = file.string() + ": shorter than a pipeline cache header; starting empty";
            data.clear();
        } else {
            std::memcpy(&header, data.data(), sizeof(header));
            if (header.headerVersion != VK_PIPELINE_CACHE_HEADER_VERSION_ONE ||
                header.vendorID != props.vendorID || header.deviceID != props.deviceID ||
                std::memcmp(header.pipelineCacheUUID, props.pipelineCacheUUID, VK_UUID_SIZE)) {
                out.note = file.string() + ": made by another device or driver; starting empty";
                data.clear();
            }
        }
    } else {
        out.note = file.string() + ": no cache file yet; starting empty";
    }
    VkPipelineCacheCreateInfo ci{};
    ci.sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO;
    ci.initialDataSize = data.size();
    ci.pInitialData = data.empty() ? nullptr : data.data();
    if (VkResult r = vkCreatePipelineCache(device, &ci, nullptr, &out.cache); r != VK_SUCCESS) {
        *error = failed("vkCreatePipelineCache", r);
        return std::nullopt;
    }
    out.loaded = !data.empty();
    return out;
}

bool save_pipeline_cache(VkDevice device, VkPipelineCache cache, const fs::path& file,
                         std::string* error) {
    size_t size = 0;
    if (VkResult r = vkGetPipelineCacheData(device, cache, &size, nullptr); r != VK_SUCCESS) {
        *error = failed("vkGetPipelineCacheData", r);
        return false;
    }
    std::string data(size, '\0');
    if (VkResult r = vkGetPipelineCacheData(device, cache, &size, data.data()); r != VK_SUCCESS) {
        *error = failed("vkGetPipelineCacheData", r);
        return false;
    }
    data.resize(size);
    const fs::path temp = file.string() + ".tmp-" + std::to_string(::getpid());
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        out.write(data.data(), static_cast<std::streamsize>(data.size()));
        out.flush();
        if (!out) {
            *error = temp.string() + ": cannot be written";
            std::error_code ec;
            fs::remove(temp, ec);
            return false;
        }
    }
    std::error_code ec;
    fs::rename(temp, file, ec);
    if (ec) {
        *error = "renaming " + temp.string() + " to " + file.string() + ": " + ec.message();
        fs::remove(temp, ec);
        return false;
    }
    return true;
}

} // namespace watergen
