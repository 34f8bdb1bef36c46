// Indexed grid meshes for render jobs (RenderJob::mesh): vertex input state for the pipeline,
// vertex + index buffers, and the indexed draw. Internal to the runner, like vulkan_internal.h.
#pragma once

#include "vulkan_internal.h"

namespace watergen::vk_detail {

// Checks the mesh (throws RunnerError naming what is wrong) and returns its attribute sizes for
// the pipeline's vertex input (vk_state::VertexInput); none for an empty mesh (the fullscreen
// triangle).
std::vector<uint32_t> mesh_attribute_sizes(const MeshData& mesh);

struct MeshBuffers {
    Buffer vertices, indices;
    uint32_t index_count = 0; // 0: no mesh
};

// Uploads the mesh into host-visible buffers owned by `scope`; index_count 0 for an empty mesh.
MeshBuffers upload_mesh(Scope& scope, const MeshData& mesh);

// Binds both buffers and records the indexed draw.
void record_mesh_draw(VkCommandBuffer cmd, const MeshBuffers& mesh);

} // namespace watergen::vk_detail
