// What an engine does with a watergen build, headless: open the build directory that
// watergen_add_shaders() generated, select the variant for the scene and the features the
// renderer wants (the nearest kept variant if the scene pruned that combination), set the
// frame's parameters, pack the uniform block as the GLSL path's reflection lays it out, create
// the pipeline in the one layout of the build's binding map (BindingLayout; with a pipeline
// cache file) and draw it. A variant whose caustics read the build's caustics pass
// (caustics=area_ratio, photon_splat) gets that pass drawn first, its texture bound as
// caustics_map. A mesh variant (geometry=mesh or tessellated) is drawn over the runtime
// library's clipmap grid around the eye (water_grid.h), with the camera in its block. Writes
// water.ppm and checks the pixels.
//
//   water_viewer [build-directory] [output.ppm] [scene] [caustics choice] [geometry]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

// The build's own C++ header (watergen_shaders.h beside manifest.json): its binding map, each
// uniform block as a struct, its variants. The namespace is the material's name.
#include "watergen_shaders.h"

#include "watergen/headless/headless_device.h"
#include "watergen/runtime/binding_layout.h"
#include "watergen/runtime/host_values.h"
#include "watergen/runtime/pass_pipeline.h"
#include "watergen/runtime/shader_build.h"
#include "watergen/runtime/uniform_writer.h"
#include "watergen/runtime/water_grid.h"

using namespace watergen;

namespace {

int fail(const std::string& what) {
    std::fprintf(stderr, "water_viewer: error: %s\n", what.c_str());
    return 1;
}

// The frame's camera: at the eye, looking down +z and 20 degrees down, 60 degrees vertical
// field of view, a square image of `size` pixels.
constexpr float kEye[3] = {0.0f, 6.0f, -20.0f};

// Stand-ins for the engine's frame: the opaque scene's colour, its positions and a sky.
// Constant images, except the positions: a flat bottom 2 m below the water spanning the caustics
// pass's default window (x and z from -5 to 5 m across the screen), so that a caustics variant
// shows the pass's pattern. Written as the shader reads them: the point less the eye.
TextureData texture_for(const TextureSlot& slot) {
    const bool cube = slot.type == "textureCube";
    if (slot.name == "scene_position") {
        constexpr uint32_t n = 32;
        TextureData t{n, n, 1, {}};
        for (uint32_t j = 0; j < n; ++j)
            for (uint32_t i = 0; i < n; ++i)
                t.rgba.insert(t.rgba.end(),
                              {-5.0f + 10.0f * (i + 0.5f) / n - kEye[0], -2.0f - kEye[1],
                               -5.0f + 10.0f * (j + 0.5f) / n - kEye[2], 1.0f});
        return t;
    }
    float texel[4] = {0.5f, 0.5f, 0.5f, 1.0f};
    if (slot.name == "scene_color") texel[0] = 0.3f, texel[1] = 0.45f, texel[2] = 0.35f;
    if (cube) texel[0] = 0.45f, texel[1] = 0.65f, texel[2] = 0.9f;
    TextureData t{4, 4, cube ? 6u : 1u, {}};
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

struct Stages {
    std::vector<uint32_t> vs, fs;
    Reflection vr, fr;
    std::vector<uint32_t> tcs, tes; // a tessellated variant's patch stages
    Reflection tcr, ter;
};

// The GLSL path's SPIR-V and reflection of a variant or a pass's shader.
std::optional<Stages> load_stages(const ShaderBuild& build, const BuildVariant& v,
                                  std::string* error) {
    const auto vs = build.spirv(v, "glsl", ShaderStage::Vertex, error);
    const auto fs = vs ? build.spirv(v, "glsl", ShaderStage::Fragment, error) : std::nullopt;
    const auto vr = fs ? build.reflection(v, "glsl", ShaderStage::Vertex, error) : std::nullopt;
    const auto fr = vr ? build.reflection(v, "glsl", ShaderStage::Fragment, error) : std::nullopt;
    if (!fr) return std::nullopt;
    Stages s{*vs, *fs, *vr, *fr, {}, {}, {}, {}};
    if (v.geometry && v.geometry->tessellated()) {
        const auto tcs = build.spirv(v, "glsl", ShaderStage::TessControl, error);
        const auto tes =
            tcs ? build.spirv(v, "glsl", ShaderStage::TessEvaluation, error) : std::nullopt;
        const auto tcr =
            tes ? build.reflection(v, "glsl", ShaderStage::TessControl, error) : std::nullopt;
        const auto ter =
            tcr ? build.reflection(v, "glsl", ShaderStage::TessEvaluation, error) : std::nullopt;
        if (!ter) return std::nullopt;
        s.tcs = *tcs, s.tes = *tes, s.tcr = *tcr, s.ter = *ter;
    }
    return s;
}

// A mesh variant's frame: the camera as its vertex stage takes it, and the grid around the
// eye with its morph range. The grid: 0.5 m cells near the eye, 32 cells a ring, 8 levels.
std::optional<WaterGrid> set_mesh_frame(const BuildVariant& v, UniformWriter& uniforms,
                                        uint32_t size, std::string* error) {
    const float pitch = -20.0f * 3.14159265f / 180.0f,
                tan_half = std::tan(30.0f * 3.14159265f / 180.0f);
    const std::vector<float> forward = {0.0f, std::sin(pitch), std::cos(pitch)};
    const std::vector<float> up = {0.0f, std::cos(pitch), -std::sin(pitch)}; // forward x right
    const WaterGridDesc desc{0.5, 32, 8};
    const WaterGrid grid =
        water_grid(desc, kEye[0], kEye[2],
                   v.geometry->tessellated() ? GridTopology::Patches : GridTopology::Triangles);
    const std::pair<const char*, std::vector<float>> values[] = {
        {"mesh_camera_right", {1.0f, 0.0f, 0.0f}},
        {"mesh_camera_up", up},
        {"mesh_camera_forward", forward},
        {"mesh_projection", {1.0f / tan_half, 1.0f / tan_half}},
        {"mesh_pixel_angle", {2.0f * tan_half / float(size)}},
        {"grid_morph_start", {float(grid.morph_start)}},
        {"grid_morph_end", {float(grid.morph_end)}}};
    for (const auto& [name, value] : values)
        if (const Write w = uniforms.set(name, value); !w.ok) {
            *error = w.error;
            return std::nullopt;
        }
    std::printf("%s over the runtime's clipmap grid: %u vertices, %zu %s, 0.5 m cells near the "
                "eye, 8 levels of 32 cells a ring\n",
                v.geometry->name.c_str(), grid.vertex_count(),
                grid.indices.size() / (grid.patch_control_points ? 4 : 3),
                grid.patch_control_points ? "patches" : "triangles");
    return grid;
}

// The variant's caustics pass, drawn as the engine would each frame before the water: the grid
// over the pass's caustics window (its default) at its default depth, the frame's sun. Drawn
// once more after the first (which JIT-compiles on lavapipe) to time a steady frame.
std::optional<TextureData> draw_caustics(const ShaderBuild& build, const BuildVariant& v,
                                         HeadlessDevice& gpu, VkPipelineCache cache,
                                         const std::vector<float>& sun, std::string* error) {
    const auto pass = build.pass(v, "caustics", error);
    const auto stages = pass ? load_stages(build, pass->shader, error) : std::nullopt;
    if (!stages) return std::nullopt;
    const PassDraw& d = pass->reference.draw;
    UniformWriter uniforms(pass->shader);
    std::vector<double> window, depth;
    for (const BlockParameter& p : pass->shader.parameters) {
        if (p.name == d.window_parameter) window = p.default_value;
        if (p.name == d.margin_parameter) depth = p.default_value;
    }
    const auto grid = pass_grid(d, window, depth.empty() ? 0.0 : depth[0], error);
    if (!grid) return std::nullopt;
    uniforms.set_frame({grid->centre, {}}); // the pass works in its grid's frame
    for (const auto& [name, value] : grid->values)
        if (const Write w = uniforms.set(name, value); !w.ok) return *error = w.error, std::nullopt;
    if (const Write w = uniforms.set("sun_direction", sun); !w.ok)
        return *error = w.error, std::nullopt;
    const auto bytes = uniforms.pack(stages->vr, error); // the pass's block is its vertex stage's
    const auto format = bytes ? pass_format(d, error) : std::nullopt;
    const VkRenderPass target = format ? gpu.render_pass(*format, error) : VK_NULL_HANDLE;
    if (!target) return std::nullopt;
    const VariantPipelineDesc desc{&stages->vs, &stages->fs, &stages->vr, &stages->fr,
                                   target,      0,           {},          cache};
    const auto pipeline = create_pass_pipeline(gpu.device(), d, desc, error);
    if (!pipeline) return std::nullopt;
    std::optional<TextureData> texture;
    double ms[2] = {0, 0};
    for (double& t : ms) {
        const auto start = std::chrono::steady_clock::now();
        texture = gpu.draw_pass(*pipeline, d, *grid, {{pass->shader.block_name, *bytes}}, error);
        t = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        if (!texture) return std::nullopt;
    }
    float lo = INFINITY, hi = -INFINITY; // the intensity (r; g and b repeat it, a = 1)
    for (size_t i = 0; i < texture->rgba.size(); i += 4)
        lo = std::fmin(lo, texture->rgba[i]), hi = std::fmax(hi, texture->rgba[i]);
    std::printf("caustics pass %s (%s) drawn first: %ux%u %s, %zu %s, intensity in [%.3f, %.3f], "
                "%.1f ms first draw, %.1f ms the next; bound as caustics_map\n",
                pass->reference.method.c_str(), pass->reference.directory.c_str(), d.texels,
                d.texels, d.format.c_str(),
                grid->points ? grid->indices.size() : grid->indices.size() / 3,
                grid->points ? "points" : "triangles", lo, hi, ms[0], ms[1]);
    return texture;
}

// An engine without the runtime library fills the build header's struct of the variant's
// uniform block instead of a UniformWriter: the same frame's values give the same bytes.
// The header's members with a host rule (HostMember) hold the values for the defaults' frame;
// an engine computes them each frame in double from what it set in world coordinates and
// seconds, as UniformWriter::pack does: host_value() of host_values.h (watergen_reflection,
// standard library only), in the frame around the eye. False and *why when an input is missing.
template <class Block>
bool set_host_members(Block& block, const BuildVariant& v,
                      const std::map<std::string, std::vector<double>>& set, std::string* why) {
    std::map<std::string, std::vector<double>> given;
    for (const BlockParameter& p : v.parameters)
        given[p.name] = p.default_value;
    for (const auto& [name, value] : set)
        given[name] = value;
    const auto eye = given.find("eye_position");
    if (eye == given.end() || eye->second.size() != 3) return true; // no frame: values as given
    const Frame frame{frame_centre_of(eye->second[0], eye->second[2]), {}};
    const GivenValues lookup = [&](const std::string& n) -> const std::vector<double>* {
        const auto it = given.find(n);
        return it == given.end() ? nullptr : &it->second;
    };
    for (const watergen_shaders::HostMember& m : Block::kHostMembers) {
        const auto rule = host_rule_from_name(m.rule);
        if (!rule) {
            *why = std::string("the header's host member '") + m.name + "' has rule '" + m.rule +
                   "', which this runtime does not know";
            return false;
        }
        HostValue h{*rule, {}};
        for (const char* in : m.inputs)
            if (in) h.inputs.emplace_back(in);
        const auto own = given.find(m.name);
        if (own == given.end()) {
            *why = std::string("the header's host member '") + m.name + "' is not a parameter";
            return false;
        }
        const auto value = host_value(h, own->second, lookup, frame, why);
        if (!value) return false;
        auto* bytes = reinterpret_cast<unsigned char*>(&block);
        for (uint32_t e = 0; e < std::max(m.elements, 1u); ++e)
            for (uint32_t c = 0; c < m.components; ++c) {
                const float f = static_cast<float>((*value)[e * m.components + c]);
                std::memcpy(bytes + m.offset + 16 * e + 4 * c, &f, sizeof f);
            }
    }
    return true;
}

// The build's C++ header packs the same bytes as the runtime's writer (GLSL path, std140).
std::optional<std::string> check_header_block(const std::string& scene, const BuildVariant& v,
                                              const std::map<std::string, std::vector<double>>& set,
                                              const std::vector<uint8_t>& packed) {
    namespace header = watergen_default;
    const auto found = std::find_if(header::kVariants.begin(), header::kVariants.end(),
                                    [&](const watergen_shaders::VariantInfo& info) {
                                        return info.scene == scene && info.key == v.key;
                                    });
    if (found == header::kVariants.end())
        return "watergen_shaders.h does not list " + scene + " " + v.key;
    return header::with_interface(
        found->interface_index, [&](auto block) -> std::optional<std::string> {
            // The members set in world coordinates, as floats (the host rules read them in
            // double from `set`).
            auto vec3 = [&](const char* name, watergen_shaders::Vec3& out) {
                const auto it = set.find(name);
                if (it == set.end() || it->second.size() != 3) return false;
                out = {static_cast<float>(it->second[0]), static_cast<float>(it->second[1]),
                       static_cast<float>(it->second[2])};
                return true;
            };
            if (!vec3("eye_position", block.eye_position))
                return std::string("watergen_shaders.h: no eye_position (3 values) was set");
            if constexpr (requires { block.sun_direction; })
                if (!vec3("sun_direction", block.sun_direction))
                    return std::string("watergen_shaders.h: no sun_direction (3 values) was set");
            std::string why;
            if (!set_host_members(block, v, set, &why)) return "watergen_shaders.h: " + why;
            if (packed.size() != sizeof block ||
                std::memcmp(packed.data(), &block, sizeof block) != 0)
                return "watergen_shaders.h's block differs from the runtime's packing";
            std::printf("watergen_shaders.h: interface %u (%zu bytes, %zu members computed on "
                        "the host) packs the same bytes; WaterParams at set %u, binding %u\n",
                        found->interface_index, sizeof block, decltype(block)::kHostMembers.size(),
                        header::bindings::WaterParams.set, header::bindings::WaterParams.binding);
            return std::nullopt;
        });
}

} // namespace

int main(int argc, char** argv) {
    const std::string dir = argc > 1 ? argv[1] : WATER_SHADER_DIR;
    const std::string image = argc > 2 ? argv[2] : "water.ppm";
    // "-": the build's first scene (for giving the arguments after it).
    const std::string scene_arg = argc > 3 && std::string(argv[3]) != "-" ? argv[3] : "";
    const std::string caustics = argc > 4 ? argv[4] : "";
    const std::string geometry = argc > 5 ? argv[5] : "";
    std::string error;
    const auto build = ShaderBuild::open(dir, &error);
    if (!build) return fail(error);
    std::printf("%s: %zu variants, scenes:", dir.c_str(), build->variants().size());
    for (const auto& s : build->scenes())
        std::printf(" %s", s.c_str());
    std::printf("\n");

    // The renderer wants Schlick Fresnel, specular highlights, animated waves and shore foam
    // (and the caustics asked for, if any).
    std::map<std::string, std::string> wanted = {{"fresnel", "schlick"},
                                                 {"specular", "blinn_phong"},
                                                 {"waves", "gerstner"},
                                                 {"foam", "shore"},
                                                 {"precision", "full"}};
    if (!caustics.empty()) wanted["caustics"] = caustics;
    if (!geometry.empty()) wanted["geometry"] = geometry;
    const std::string scene = scene_arg.empty() ? build->scenes().front() : scene_arg;
    const Selection sel = build->select(scene, wanted, Fallback::NearestKept);
    if (!sel.ok()) return fail(sel.error);
    const BuildVariant& v = *sel.variant;
    std::printf("scene %s: selected %s\n", scene.c_str(), v.key.c_str());
    for (const auto& c : sel.changed)
        std::printf("  pruned by the scene, nearest kept variant: %s\n", c.c_str());

    const auto stages = load_stages(*build, v, &error);
    if (!stages) return fail(error);
    const std::vector<float> sun = {-0.3f, -0.8f, 0.5f};

    UniformWriter uniforms(v);
    const std::map<std::string, std::vector<double>> frame_values = {
        {"eye_position", {kEye[0], kEye[1], kEye[2]}}, {"sun_direction", {sun[0], sun[1], sun[2]}}};
    for (const auto& [name, value] : frame_values) {
        const Write w = uniforms.set(name, std::span<const double>(value));
        if (!w.ok) return fail(w.error);
        if (!w.note.empty()) std::printf("  %s\n", w.note.c_str());
    }
    constexpr uint32_t kSize = 128;
    std::optional<WaterGrid> grid;
    if (v.geometry) {
        grid = set_mesh_frame(v, uniforms, kSize, &error);
        if (!grid) return fail(error);
    }
    const auto bytes = uniforms.pack(stages->fr, &error);
    if (!bytes) return fail(error);
    if (!v.geometry)
        if (auto why = check_header_block(scene, v, frame_values, *bytes)) return fail(*why);

    auto gpu = HeadlessDevice::create({}, &error);
    if (!gpu) return fail(error);
    auto cache = load_pipeline_cache(gpu->physical(), gpu->device(), "pipelines.bin", &error);
    if (!cache) return fail(error);
    // One pipeline layout for every variant of the build, from its binding map: an engine
    // makes it once and keeps its descriptor sets bound across variants.
    const auto layout = BindingLayout::create(gpu->device(), build->bindings(), &error);
    if (!layout) return fail(error);
    std::printf("one pipeline layout for every variant: binding map %s, %zu slots in %zu sets\n",
                build->bindings().map.c_str(), build->bindings().slots.size(),
                layout->set_layouts().size());
    VariantPipelineDesc desc{&stages->vs,        &stages->fs, &stages->vr, &stages->fr,
                             gpu->render_pass(), 0,           {},          cache->cache};
    desc.layout = &*layout;
    for (const auto& [id, value] : v.specialization) // specialized build mode: the selectors
        desc.specialization[id] = static_cast<float>(value);
    // A mesh variant: its grid's vertex input; a tessellated one also its patch stages, in a
    // layout of its own (the build's BindingLayout serves vertex and fragment stages).
    PipelineGeometry mesh;
    if (v.geometry) {
        mesh.attribute_sizes = v.geometry->attribute_sizes();
        mesh.patch_control_points = v.geometry->patch_control_points;
        if (v.geometry->tessellated()) {
            desc.layout = nullptr;
            desc.tess_control_spirv = &stages->tcs;
            desc.tess_evaluation_spirv = &stages->tes;
            desc.tess_control_reflection = &stages->tcr;
            desc.tess_evaluation_reflection = &stages->ter;
        }
    }
    auto pipeline = v.geometry ? VariantPipeline::create(gpu->device(), desc, mesh, &error)
                               : VariantPipeline::create(gpu->device(), desc, &error);
    if (!pipeline) return fail(error);
    std::optional<TextureData> caustics_map;
    if (v.passes.count("caustics")) {
        caustics_map = draw_caustics(*build, v, *gpu, cache->cache, sun, &error);
        if (!caustics_map) return fail(error);
    }
    if (!save_pipeline_cache(gpu->device(), cache->cache, "pipelines.bin", &error))
        return fail(error);
    vkDestroyPipelineCache(gpu->device(), cache->cache, nullptr);

    HeadlessDraw draw;
    draw.width = draw.height = kSize;
    if (grid) {
        draw.vertices = &grid->vertices;
        draw.indices = &grid->indices;
        draw.attribute_sizes = v.geometry->attribute_sizes();
        draw.patch_control_points = grid->patch_control_points;
    }
    draw.uniforms[v.block_name] = *bytes;
    for (const TextureSlot& t : v.textures)
        draw.textures[t.name] =
            t.name == "caustics_map" && caustics_map ? *caustics_map : texture_for(t);
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
    for (const auto& m : gpu->validation_messages())
        std::printf("  validation: %s\n", m.c_str());
    if (bad || !(hi - lo > 0.01f) || !gpu->validation_messages().empty())
        return fail("the image is not a plausible water surface");
    if (!write_ppm(image, rgba, draw.width, draw.height)) return fail("cannot write " + image);
    std::printf("wrote %s\n", image.c_str());
    return 0;
}
