// One draw of a VariantPipeline into an offscreen target of the headless device, prepared once
// (target, descriptors written from the inputs, vertex and index buffers, the recorded commands)
// and submitted as often as wanted: the test runner's timed draws (watergen/runner/
// vulkan_runner.h) and HeadlessDevice::draw() / draw_pass() (one submit each) are this draw.
// Errors are data, as for HeadlessDevice.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "watergen/headless/headless_device.h"
#include "watergen/headless/texture_data.h"
#include "watergen/runtime/variant_pipeline.h"

namespace watergen {

struct DrawTarget {
    uint32_t width = 256, height = 256;
    // RGBA32F (the water's), or a companion pass's pass_format().
    VkFormat format = VK_FORMAT_R32G32B32A32_SFLOAT;
    float clear = 0; // every channel
};

// What the descriptors and push constants are written from, by binding name: the bytes of each
// uniform block (a uniform buffer, or the pipeline's push-constant block), the
// image of each sampled-image and combined image-sampler binding (every sampler: `filter`, clamp
// to edge). A binding with no entry fails the draw, naming it; entries no binding uses are
// ignored. Read while create() runs, not kept.
struct DrawBindings {
    const std::map<std::string, std::vector<uint8_t>>* uniforms = nullptr;
    // In place of `uniforms`: the bytes of the pipeline's one uniform block, whatever its name
    // (a job of the test runner carries one block): its uniform buffer or its push-constant
    // block; more than one uniform binding, or one and a push-constant block, is an error.
    const std::vector<uint8_t>* sole_uniforms = nullptr;
    const std::map<std::string, TextureData>* textures = nullptr;
    TextureFilter filter = TextureFilter::Linear;
};

// The vertices drawn. No indices: the fullscreen triangle (3 vertices from gl_VertexIndex, no
// buffers). Else an indexed list from one interleaved float vertex buffer at binding 0,
// attribute i with attribute_sizes[i] floats (the pipeline's PipelineGeometry), triangles,
// points or patches. Read while create() runs, not kept.
struct DrawGeometry {
    const std::vector<float>* vertices = nullptr;
    const std::vector<uint32_t>* indices = nullptr;
    std::vector<uint32_t> attribute_sizes;
    bool points = false;
    std::string what = "mesh"; // names the geometry in errors ("grid")
    // > 0: the indices name patches of this many control points (the pipeline's
    // PipelineGeometry::patch_control_points), not triangles.
    uint32_t patch_control_points = 0;
};

namespace headless_detail {
struct PreparedDraw;
}

class OffscreenDraw {
  public:
    // `pipeline` was made with device.render_pass() (RGBA32F) or render_pass(target.format);
    // it and the device outlive the draw. nullptr and `error` for a target the device cannot
    // draw, a binding without input, geometry that does not fit, or a failed Vulkan call.
    static std::unique_ptr<OffscreenDraw>
    create(HeadlessDevice& device, const VariantPipeline& pipeline, const DrawTarget& target,
           const DrawBindings& bindings, const DrawGeometry& geometry, std::string* error);
    ~OffscreenDraw();
    OffscreenDraw(const OffscreenDraw&) = delete;
    OffscreenDraw& operator=(const OffscreenDraw&) = delete;

    // Submits the recorded draw and waits for it. `ms` (may be null): the draw's GPU time from
    // timestamp queries (top of pipe before the render pass to bottom of pipe after it, scaled
    // by timestampPeriod), or the CPU wall time of submit + wait where the queue cannot write
    // timestamps.
    bool submit(double* ms, std::string* error);

    // The target after the last submit: floats per texel as its format has channels (4 for
    // RGBA32F, pass_format_channels()), row 0 at the top (framebuffer y = 0).
    std::optional<std::vector<float>> read_back(std::string* error);

  private:
    explicit OffscreenDraw(std::unique_ptr<headless_detail::PreparedDraw> prepared);
    std::unique_ptr<headless_detail::PreparedDraw> prepared_;
};

} // namespace watergen
