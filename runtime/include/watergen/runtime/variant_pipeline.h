// A small Vulkan helper for an engine: the descriptor set layouts, pipeline layout and graphics
// pipeline of a built variant, from its reflection, and a VkPipelineCache kept in a file on
// disk. Part of watergen::runtime. The engine owns the device, render pass and everything drawn.
//
// The pipeline draws the generated vertex stage as it is (a fullscreen triangle from
// gl_VertexIndex: vkCmdDraw(cmd, 3, 1, 0, 0), no vertex buffers), with viewport and scissor as
// dynamic state, no blending, no depth, no culling; a companion pass (pass_pipeline.h) passes a
// PipelineGeometry instead: its grid's vertex input, triangles or points, additive blending;
// a mesh may instead be patches for tessellation stages, and ask for back faces culled. With
// tessellation stages (VariantPipelineDesc), the unions below span all four stages.
// Descriptor layouts are the union of both stages' bindings (a binding both declare agrees on
// kind and name, and keeps the larger block size), one layout per set number (gaps get empty
// layouts), with the stage flags of the stages that use each binding; or, given a
// BindingLayout (binding_layout.h), that one layout of the build's binding map, shared by every
// pipeline of the build and not re-derived (each stage's descriptors checked against it).
//
// Push constants: a stage's Reflection::push_constant (the parameter block, when the build's
// binding map makes it a push constant) is no descriptor. With a layout of its own, the
// pipeline layout has one push-constant range at offset 0 of both stages' block (one name; the
// larger block_size rounded up to 4 bytes), with the stage flags of the stages that declare it;
// with a shared layout, the BindingLayout's range (its size, vertex and fragment stages). The
// engine records vkCmdPushConstants(cmd, layout(), push_constant_stages(), 0, n, bytes) with
// the block's bytes (UniformWriter::pack(), the same std140 / cbuffer offsets as a uniform
// buffer), n = push_constant()->block_size rounded up to 4.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "watergen/runtime/binding_layout.h"
#include "watergen/runtime/reflection.h"

namespace watergen {

// Limits every Vulkan device meets (the spec's minimums of maxVertexInputAttributes and
// maxTessellationPatchSize): a PipelineGeometry past them is refused before a driver sees it.
constexpr size_t kMaxVertexAttributes = 16;
constexpr uint32_t kMaxPatchControlPoints = 32;
// Whether a VkFormat's value is a core colour format (not depth / stencil, not block
// compressed): what a render pass's colour attachment may be; the device then says whether it
// renders to it.
inline bool is_colour_format(int64_t format) {
    return format >= VK_FORMAT_R4G4_UNORM_PACK8 && format <= VK_FORMAT_E5B9G9R9_UFLOAT_PACK32;
}

// How the pipeline draws when it is not the water's fullscreen triangle: a companion pass's
// grid (pass_geometry() in pass_pipeline.h makes one from the pass's draw description).
struct PipelineGeometry {
    // Floats of each vertex attribute (1 to 4; attribute i at location i, interleaved in one
    // buffer at binding 0). Empty: no vertex input (the fullscreen triangle).
    std::vector<uint32_t> attribute_sizes;
    bool points = false;         // a point list; else a triangle list
    bool additive_blend = false; // ONE + ONE into the target; else no blending
    // > 0: a patch list of this many control points (VK_PRIMITIVE_TOPOLOGY_PATCH_LIST), for a
    // pipeline with tessellation stages (which then need it); 0: no patches.
    uint32_t patch_control_points = 0;
    // Cull back faces (front faces are counter-clockwise in the framebuffer); else no culling.
    // For checking which way a geometry's triangles wind.
    bool cull_back_faces = false;
};

struct VariantPipelineDesc {
    const std::vector<uint32_t>* vertex_spirv = nullptr;
    const std::vector<uint32_t>* fragment_spirv = nullptr;
    const Reflection* vertex_reflection = nullptr;
    const Reflection* fragment_reflection = nullptr;
    VkRenderPass render_pass = VK_NULL_HANDLE;
    uint32_t subpass = 0;
    // Float specialization constants by constant_id, given to both stages (the variant's
    // selectors in the specialized build mode).
    std::map<uint32_t, float> specialization;
    VkPipelineCache cache = VK_NULL_HANDLE; // may be null
    // VkGraphicsPipelineCreateInfo::flags: e.g. VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR
    // for a driver's compiler statistics (VK_KHR_pipeline_executable_properties).
    VkPipelineCreateFlags flags = 0;
    // The build's one layout (BindingLayout::create from ShaderBuild::bindings()); it must
    // outlive the pipeline. Null: a layout of this pipeline's own from its reflection.
    const BindingLayout* layout = nullptr;
    // The device's VkPhysicalDeviceLimits::maxPushConstantsSize: a layout of the pipeline's
    // own with a larger push-constant block is an error naming both. The default is the 128
    // bytes every Vulkan device has. (A shared layout was checked by BindingLayout::create.)
    uint32_t max_push_constants_size = kGuaranteedPushConstantsSize;
    // Tessellation control and evaluation stages (both or neither; last here, so positional
    // initialisers of the fields above still hold): drawn between the vertex and fragment
    // stages, from patches (PipelineGeometry::patch_control_points), with a layout of the
    // pipeline's own (`layout` null: a BindingLayout serves vertex and fragment stages only);
    // the device must have enabled the tessellationShader feature.
    const std::vector<uint32_t>* tess_control_spirv = nullptr;
    const std::vector<uint32_t>* tess_evaluation_spirv = nullptr;
    const Reflection* tess_control_reflection = nullptr;
    const Reflection* tess_evaluation_reflection = nullptr;
};

class VariantPipeline {
  public:
    // std::nullopt and `error` naming the Vulkan call and its VkResult (or the missing input,
    // or stages whose descriptors or push-constant blocks disagree or do not fit).
    static std::optional<VariantPipeline> create(VkDevice device, const VariantPipelineDesc& desc,
                                                 std::string* error);
    // The same with another geometry (a companion pass's grid: create_pass_pipeline()).
    static std::optional<VariantPipeline> create(VkDevice device, const VariantPipelineDesc& desc,
                                                 const PipelineGeometry& geometry,
                                                 std::string* error);
    VariantPipeline(VariantPipeline&& other) noexcept;
    VariantPipeline& operator=(VariantPipeline&& other) noexcept;
    VariantPipeline(const VariantPipeline&) = delete;
    VariantPipeline& operator=(const VariantPipeline&) = delete;
    ~VariantPipeline();

    VkPipeline pipeline() const { return pipeline_; }
    VkPipelineLayout layout() const { return shared_ ? shared_->layout() : layout_; }
    const std::vector<VkDescriptorSetLayout>& set_layouts() const {
        return shared_ ? shared_->set_layouts() : set_layouts_;
    }
    // The bindings of set `set` the stages read (union of both), for writing descriptors; with
    // a shared layout its other slots are not read and need not be written.
    const std::vector<DescriptorBinding>& bindings(uint32_t set) const { return bindings_[set]; }
    // Descriptor counts for a pool holding `copies` of every set (of the shared layout: every
    // slot of the map).
    std::vector<VkDescriptorPoolSize> pool_sizes(uint32_t copies = 1) const;

    // The push-constant block the stages read (name, block_size: the larger of the two stages',
    // members: that stage's); null when neither stage declares one.
    const DescriptorBinding* push_constant() const { return push_block_ ? &*push_block_ : nullptr; }
    // The stage flags vkCmdPushConstants must name: the range's (those of the stages declaring
    // the block; vertex and fragment with a shared layout); 0 without a range.
    VkShaderStageFlags push_constant_stages() const { return push_range_.stageFlags; }
    // Bytes of the layout's push-constant range (at offset 0); 0 without one. At least
    // push_constant()->block_size rounded up to 4.
    uint32_t push_constant_size() const { return push_range_.size; }

  private:
    // Both stages' bindings by (set, binding), with the stage flags of the stages reading each.
    using StageUnion =
        std::map<std::pair<uint32_t, uint32_t>, std::pair<DescriptorBinding, VkShaderStageFlags>>;
    VariantPipeline() = default;
    void destroy();
    bool create_own_layout(VkDevice device, const StageUnion& all, uint32_t sets,
                           std::string* error);
    // The union of both stages' push-constant blocks into push_block_ and push_range_; false
    // and `error` when they disagree or the range exceeds `max_size` (own layout).
    bool union_push_constants(const VariantPipelineDesc& d, std::string* error);
    VkDevice device_ = VK_NULL_HANDLE;
    std::vector<VkDescriptorSetLayout> set_layouts_;
    std::vector<std::vector<DescriptorBinding>> bindings_;
    VkPipelineLayout layout_ = VK_NULL_HANDLE; // own; null with a shared one
    const BindingLayout* shared_ = nullptr;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    std::optional<DescriptorBinding> push_block_;
    VkPushConstantRange push_range_{}; // size 0: none
};

// A descriptor's type; never asked of a PushConstant (no descriptor), for which it says
// VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER (the block's form as a buffer).
VkDescriptorType descriptor_type(DescriptorKind kind);
// Descriptor counts by type for one descriptor of each of `kinds`, `copies` times over: the
// pool sizes of sets holding them.
std::vector<VkDescriptorPoolSize> pool_sizes_of(const std::vector<DescriptorKind>& kinds,
                                                uint32_t copies = 1);

// A VkPipelineCache whose initial data comes from a file and that save() writes back. A
// missing file, or one the driver rejects (another device, driver or version: the header is
// checked against the device's vendor id, device id and pipelineCacheUUID), starts an empty
// cache; `loaded` says which.
struct PipelineCacheFile {
    VkPipelineCache cache = VK_NULL_HANDLE;
    bool loaded = false; // the file's data was accepted
    std::string note;    // why it was not, when it was not
};

std::optional<PipelineCacheFile> load_pipeline_cache(VkPhysicalDevice physical, VkDevice device,
                                                     const std::filesystem::path& file,
                                                     std::string* error);
// Writes the cache's data to a temporary file beside `file`, then renames it into place: a
// crash leaves the old file or the new one, never a torn one.
bool save_pipeline_cache(VkDevice device, VkPipelineCache cache, const std::filesystem::path& file,
                         std::string* error);

} // namespace watergen
