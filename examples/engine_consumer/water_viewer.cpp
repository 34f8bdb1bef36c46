// What an engine does with a watergen build, headless: open the build directory that
// watergen_add_shaders() generated, select the variant for the scene and the features the
// renderer wants (the nearest kept variant if the scene pruned that combination), set the
// frame's parameters, pack the uniform block as the GLSL path's reflection lays it out, create
// the pipeline (with a pipeline cache file) and draw it. Writes water.ppm and checks the pixels.
//
//   water_viewer [build-directory] [output.ppm]
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "watergen/runtime/headless_gpu.h"
#include "watergen/runtime/shader_build.h"
#include "watergen/runtime/uniform_writer.h"

using namespace watergen;

namespace {

int fail(const std::string& what) {
    std::fprintf(stderr, "water_viewer: error: %s\n", what.c_str());
    return 1;
}

// Stand-ins for the engine's frame: the opaque scene's colour and world positions (2 m below the
// water), and a sky: constant images, enough to shade the water.
HeadlessTexture texture_for(const TextureSlot& slot) {
    const bool cube = slot.type == "textureCube";
    float texel[4] = {0.5f, 0.5f, 0.5f, 1.0f};
    if (slot.name == "scene_color") texel[0] = 0.3f, texel[1] = 0.45f, texel[2] = 0.35f;
    if (slot.name == "scene_position") texel[0] = 0.0f, texel[1] = -2.0f, texel[2] = 10.0f;
    if (cube) texel[0] = 0.45f, texel[1] = 0.65f, texel[2] = 0.9f;
    HeadlessTexture t{4, 4, cube ? 6u : 1u, {}};
    for (size_t i = 0; i < size_t(t.width) * t.height * t.layers; ++i)
        t.rgba.insert(t.rgba.end(), texel, texel + 4);
    return t;
}

bool write_ppm(const std::string& path, const std::vector<float>& rgba, uint32_t w, uint32_t h) {
    std::ofstream out(path, std::ios::binary);
    out << "P6\n" << w << " " << h << "\n255\n";
    for (size_t p = 0; p < size_t(w) * h; ++p)
        for (int c = 0; c < 3; ++c) {
            const float v = std::fmin(std::fmax(rgba[p * 4 + c], 0.0f), 1.0f);
            out.put(static_cast<char>(std::lround(std::pow(v, 1.0f / 2.2f) * 255.0f)));
        }
    return bool(out);
}

} // namespace

int main(int argc, char** argv) {
    const std::string dir = argc > 1 ? argv[1] : WATER_SHADER_DIR;
    const std::string image = argc > 2 ? argv[2] : "water.ppm";
    std::string error;
    const auto build = ShaderBuild::open(dir, &error);
    if (!build) return fail(error);
    std::printf("%s: %zu variants, scenes:", dir.c_str(), build->variants().size());
    for (const auto& s : build->scenes())
        std::printf(" %s", s.c_str());
    std::printf("\n");

    // The renderer wants Schlick Fresnel, specular highlights, animated waves and shore foam.
    const Selection sel = build->select(build->scenes().front(),
                                        {{"fresnel", "schlick"},
                                         {"specular", "blinn_phong"},
                                         {"waves", "gerstner"},
                                         {"foam", "shore"},
                                         {"precision", "full"}},
                                        Fallback::NearestKept);
    if (!sel.ok()) return fail(sel.error);
    const BuildVariant& v = *sel.variant;
    std::printf("selected %s\n", v.key.c_str());
    for (const auto& c : sel.changed)
        std::printf("  pruned by the scene, nearest kept variant: %s\n", c.c_str());

    const auto vs = build->spirv(v, "glsl", ShaderStage::Vertex, &error);
    const auto fs = vs ? build->spirv(v, "glsl", ShaderStage::Fragment, &error) : std::nullopt;
    const auto vr = fs ? build->reflection(v, "glsl", ShaderStage::Vertex, &error) : std::nullopt;
    const auto fr = vr ? build->reflection(v, "glsl", ShaderStage::Fragment, &error) : std::nullopt;
    if (!fr) return fail(error);

    UniformWriter uniforms(v);
    for (const auto& [name, value] :
         std::initializer_list<std::pair<const char*, std::vector<float>>>{
             {"eye_position", {0.0f, 6.0f, -20.0f}}, {"sun_direction", {-0.3f, -0.8f, 0.5f}}}) {
        const Write w = uniforms.set(name, value);
        if (!w.ok) return fail(w.error);
        if (!w.note.empty()) std::printf("  %s\n", w.note.c_str());
    }
    const auto bytes = uniforms.pack(*fr, &error);
    if (!bytes) return fail(error);

    auto gpu = HeadlessGpu::create(&error);
    if (!gpu) return fail(error);
    auto cache = load_pipeline_cache(gpu->physical(), gpu->device(), "pipelines.bin", &error);
    if (!cache) return fail(error);
    VariantPipelineDesc desc{&*vs, &*fs, &*vr, &*fr, gpu->render_pass(), 0, {}, cache->cache};
    for (const auto& [id, value] : v.specialization) // specialized build mode: the selectors
        desc.specialization[id] = static_cast<float>(value);
    auto pipeline = VariantPipeline::create(gpu->device(), desc, &error);
    if (!pipeline) return fail(error);
    if (!save_pipeline_cache(gpu->device(), cache->cache, "pipelines.bin", &error))
        return fail(error);
    vkDestroyPipelineCache(gpu->device(), cache->cache, nullptr);

    HeadlessDraw draw;
    draw.width = draw.height = 128;
    draw.uniforms[v.block_name] = *bytes;
    for (const TextureSlot& t : v.textures)
        draw.textures[t.name] = texture_for(t);
    const std::vector<float> rgba = gpu->draw(*pipeline, draw, &error);
    if (rgba.empty()) return fail(error);

    float lo = INFINITY, hi = -INFINITY;
    size_t bad = 0;
    for (size_t i = 0; i < rgba.size(); i += 4)
        for (int c = 0; c < 3; ++c) {
            const float f = rgba[i + c];
            if (!std::isfinite(f)) ++bad;
            lo = std::fmin(lo, f);
            hi = std::fmax(hi, f);
        }
    std::printf("drew %ux%u on %s (pipeline cache %s): rgb in [%.4f, %.4f], %zu non-finite\n",
                draw.width, draw.height, gpu->device_name().c_str(),
                cache->loaded ? "loaded" : "new", lo, hi, bad);
    for (const auto& m : gpu->messages())
        std::printf("  validation: %s\n", m.c_str());
    if (bad || !(hi - lo > 0.01f) || !gpu->messages().empty())
        return fail("the image is not a plausible water surface");
    if (!write_ppm(image, rgba, draw.width, draw.height)) return fail("cannot write " + image);
    std::printf("wrote %s\n", image.c_str());
    return 0;
}
