// Indexed grid meshes for render jobs (RenderJob::mesh): vertex input state for the pipeline,
// vertex + index buffers, and the indexed draw. Internal to the runner, like vulkan_internal.h.
#pragma once

#include "vulkan_internal.h"

namespace watergen::vk_detail {

// Storage the pipeline's VkPipelineVertexInputStateCreateInfo points into; keep it alive until
// the pipeline is created.
struct MeshInputState {
    VkVertexInputBindingDescription binding{};
    std::vector<VkVertexInputAttributeDescription> attributes;
};

// Checks the mesh (throws RunnerError naming what is wrong) and points `info` at `state`.
// Leaves `info` untouched for an empty mesh (the fullscreen triangle).
void describe_mesh_input(const MeshData& mesh, MeshInputState& state,
                         VkPipelineVertexInputStateCreateInfo& info);

struct MeshBuffers {
    Buffer vertices, indices;
    uint32_t index_count = 0; // 0: no mesh
};

// Uploads the mesh into host-visible buffers owned by `scope`; index_count 0 for an empty mesh.
MeshBuffers upload_mesh(Scope& scope, const MeshData& mesh);

// Binds both buffers and records the indexed draw.
void record_mesh_draw(VkCommandBuffer cmd, const MeshBuffers& mesh);

} // namespace watergen::vk_detail
