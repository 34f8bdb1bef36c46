// The engine's draws through the runtime library (see engine_draw_support.h).
#include "engine_draw_support.h"

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>

#include "watergen/runtime/pass_pipeline.h"
#include "watergen/runtime/uniform_writer.h"

namespace watergen::test {

namespace {

struct StageFiles {
    std::vector<uint32_t> vs, fs;
    Reflection vr, fr;
};

StageFiles stage_files(const ShaderBuild& b, const BuildVariant& v, const std::string& lang) {
    std::string error;
    const auto vs = b.spirv(v, lang, ShaderStage::Vertex, &error);
    const auto fs = b.spirv(v, lang, ShaderStage::Fragment, &error);
    const auto vr = b.reflection(v, lang, ShaderStage::Vertex, &error);
    const auto fr = b.reflection(v, lang, ShaderStage::Fragment, &error);
    INFO(error);
    REQUIRE((vs && fs && vr && fr));
    return {*vs, *fs, *vr, *fr};
}

void set_values(UniformWriter& writer, const std::map<std::string, std::vector<double>>& values) {
    for (const auto& [name, v] : values) {
        if (!writer.has(name) || writer.computed(name)) continue;
        const Write w = writer.set(name, std::span<const double>(v));
        INFO(name << ": " << w.error);
        REQUIRE(w.ok);
    }
}

} // namespace

HeadlessDevice& engine_gpu() {
    static std::unique_ptr<HeadlessDevice> g = [] {
        std::string error;
        auto created = HeadlessDevice::create({}, &error);
        if (!created) FAIL("no Vulkan device: " << error);
        return created;
    }();
    return *g;
}

EngineDraw engine_draw(const ShaderBuild& b, const BuildVariant& v, const std::string& lang,
                       const std::map<std::string, std::vector<double>>& values,
                       const std::map<std::string, TextureData>& textures, uint32_t size,
                       VkPipelineCache cache, const BindingLayout* layout) {
    const StageFiles files = stage_files(b, v, lang);
    UniformWriter writer(v);
    set_values(writer, values);
    std::string error;
    const auto bytes = writer.pack(files.fr, &error);
    REQUIRE(bytes);
    VariantPipelineDesc desc{&files.vs, &files.fs, &files.vr, &files.fr, engine_gpu().render_pass(),
                             0,         {},        cache};
    desc.layout = layout;
    auto pipeline = VariantPipeline::create(engine_gpu().device(), desc, &error);
    INFO(error);
    REQUIRE(pipeline);
    HeadlessDraw draw;
    draw.width = draw.height = size;
    draw.uniforms[v.block_name] = *bytes;
    draw.textures = textures;
    EngineDraw out{engine_gpu().draw(*pipeline, draw, &error), *bytes};
    REQUIRE(out.rgba.size() == size_t(size) * size * 4);
    return out;
}

EnginePass engine_pass(const ShaderBuild& b, const BuildPass& pass, const std::string& lang,
                       const std::map<std::string, std::vector<double>>& values, uint32_t timed) {
    const StageFiles files = stage_files(b, pass.shader, lang);
    const PassDraw& d = pass.reference.draw;
    std::string error;
    const auto grid =
        pass_grid(d, values.at(d.window_parameter), values.at(d.margin_parameter)[0], &error);
    INFO(error);
    REQUIRE(grid);
    UniformWriter writer(pass.shader);
    writer.set_frame({grid->centre, {}}); // the grid's frame (build_pass.h)
    set_values(writer, values);
    for (const auto& [name, v] : grid->values)
        REQUIRE(writer.set(name, v).ok);
    const auto bytes = writer.pack(files.vr, &error); // the one block is the vertex stage's
    REQUIRE(bytes);
    const auto format = pass_format(d, &error);
    REQUIRE(format);
    HeadlessDevice& gpu = engine_gpu();
    const VkRenderPass target = gpu.render_pass(*format, &error);
    REQUIRE(target);
    VariantPipelineDesc desc{&files.vs, &files.fs, &files.vr, &files.fr,
                             target,    0,         {},        VK_NULL_HANDLE};
    const auto pipeline = create_pass_pipeline(gpu.device(), d, desc, &error);
    REQUIRE(pipeline);
    const std::map<std::string, std::vector<uint8_t>> uniforms{{pass.shader.block_name, *bytes}};
    EnginePass out;
    for (uint32_t i = 0; i <= timed; ++i) {
        const auto start = std::chrono::steady_clock::now();
        auto texture = gpu.draw_pass(*pipeline, d, *grid, uniforms, &error);
        const std::chrono::duration<double, std::milli> ms =
            std::chrono::steady_clock::now() - start;
        REQUIRE(texture);
        if (i > 0) out.draw_ms.push_back(ms.count());
        out.texture = std::move(*texture);
    }
    REQUIRE(out.texture.rgba.size() == size_t(d.texels) * d.texels * 4);
    for (size_t i = 0; i < out.texture.rgba.size(); i += 4)
        out.intensity.push_back(out.texture.rgba[i]);
    return out;
}

double max_abs_difference(const std::vector<float>& a, const std::vector<float>& b) {
    return max_abs_difference(std::vector<double>(a.begin(), a.end()),
                              std::vector<double>(b.begin(), b.end()));
}

double max_abs_difference(const std::vector<double>& a, const std::vector<double>& b) {
    REQUIRE(a.size() == b.size());
    double m = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        REQUIRE(std::isfinite(a[i]));
        m = std::max(m, std::abs(a[i] - b[i]));
    }
    return m;
}

} // namespace watergen::test
