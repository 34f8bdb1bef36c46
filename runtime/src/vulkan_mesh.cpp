// Indexed grid meshes for render jobs (see vulkan_mesh.h).
#include "vulkan_mesh.h"

#include <fmt/format.h>

#include <algorithm>

namespace watergen::vk_detail {
namespace {

uint32_t floats_per_vertex(const MeshData& mesh) {
    uint32_t n = 0;
    for (uint32_t a : mesh.attribute_sizes)
        n += a;
    return n;
}

void check(const MeshData& mesh) {
    if (mesh.attribute_sizes.empty())
        throw RunnerError("mesh has indices but no vertex attributes");
    for (size_t i = 0; i < mesh.attribute_sizes.size(); ++i)
        if (mesh.attribute_sizes[i] < 1 || mesh.attribute_sizes[i] > 4)
            throw RunnerError(fmt::format("mesh attribute {} has {} floats; 1 to 4 are supported",
                                          i, mesh.attribute_sizes[i]));
    const uint32_t stride = floats_per_vertex(mesh);
    if (mesh.vertices.empty() || mesh.vertices.size() % stride != 0)
        throw RunnerError(
            fmt::format("mesh has {} vertex floats, not a whole number of {}-float vertices",
                        mesh.vertices.size(), stride));
    if (!mesh.points && mesh.indices.size() % 3 != 0)
        throw RunnerError(
            fmt::format("mesh has {} indices, not whole triangles", mesh.indices.size()));
    const size_t vertex_count = mesh.vertices.size() / stride;
    const uint32_t largest = *std::max_element(mesh.indices.begin(), mesh.indices.end());
    if (largest >= vertex_count)
        throw RunnerError(
            fmt::format("mesh index {} is past its {} vertices", largest, vertex_count));
}

} // namespace

std::vector<uint32_t> mesh_attribute_sizes(const MeshData& mesh) {
    if (mesh.empty()) return {};
    check(mesh);
    return mesh.attribute_sizes;
}

MeshBuffers upload_mesh(Scope& scope, const MeshData& mesh) {
    MeshBuffers out;
    if (mesh.empty()) return out;
    check(mesh);
    const size_t vertex_bytes = mesh.vertices.size() * sizeof(float);
    const size_t index_bytes = mesh.indices.size() * sizeof(uint32_t);
    // Host-visible like every runner buffer; host writes before the submit need no barrier.
    out.vertices = create_buffer(scope, vertex_bytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    write_buffer(scope.ctx(), out.vertices, mesh.vertices.data(), vertex_bytes);
    out.indices = create_buffer(scope, index_bytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    write_buffer(scope.ctx(), out.indices, mesh.indices.data(), index_bytes);
    out.index_count = static_cast<uint32_t>(mesh.indices.size());
    return out;
}

void record_mesh_draw(VkCommandBuffer cmd, const MeshBuffers& mesh) {
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &mesh.vertices.buffer, &offset);
    vkCmdBindIndexBuffer(cmd, mesh.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, mesh.index_count, 1, 0, 0, 0);
}

} // namespace watergen::vk_detail
