// Render jobs: exact pixels from gl_FragCoord, textures + samplers + uniforms read back
// exactly, cube maps, errors naming what the job forgot, timing fields.
#include "runner_support.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

using namespace watergen;

namespace {

// Every output is a small dyadic rational (at most ~10 significant bits), so each float
// operation in the shader is exact whatever the driver does about FMA contraction or
// evaluation order; with one sample per pixel gl_FragCoord is exactly the pixel centre
// (x + 0.5, y + 0.5). Hence the expected floats are compared with tolerance 0.
const char* kFragCoord = R"(#version 450
layout(location = 0) out vec4 color;
void main() {
    vec2 p = gl_FragCoord.xy;
    color = vec4(p.x, p.y, p.x * 0.5 + p.y * 0.25, p.x - p.y);
}
)";

void check_fragcoord_image(const RenderResult& r) {
    REQUIRE(r.rgba.size() == size_t{r.width} * r.height * 4);
    size_t mismatches = 0;
    for (uint32_t y = 0; y < r.height; ++y) {
        for (uint32_t x = 0; x < r.width; ++x) {
            const float fx = static_cast<float>(x) + 0.5f, fy = static_cast<float>(y) + 0.5f;
            const float expected[4] = {fx, fy, fx * 0.5f + fy * 0.25f, fx - fy};
            const float* got = &r.rgba[(size_t{y} * r.width + x) * 4];
            for (int c = 0; c < 4; ++c) {
                if (got[c] != expected[c] && mismatches++ < 5)
                    UNSCOPED_INFO("pixel (" << x << "," << y << ") channel " << c << ": got "
                                            << got[c] << " expected " << expected[c]);
            }
        }
    }
    CHECK(mismatches == 0);
}

// Texel value at (x, y) of layer `layer` of texture `id`: distinct per texel, per layer and
// per texture, all small dyadic rationals (exact through `* scale + bias` below).
void texel(uint32_t id, uint32_t layer, uint32_t x, uint32_t y, float out[4]) {
    out[0] = static_cast<float>(x) + 1.0f;
    out[1] = static_cast<float>(y) * 0.5f;
    out[2] = static_cast<float>(id * 8 + layer);
    out[3] = -0.125f * static_cast<float>(x + 16 * y);
}

TextureData make_texture(uint32_t id, uint32_t w, uint32_t h, uint32_t layers) {
    TextureData t{w, h, layers, {}};
    t.rgba.resize(size_t{w} * h * layers * 4);
    for (uint32_t l = 0; l < layers; ++l)
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x)
                texel(id, l, x, y, &t.rgba[((size_t{l} * h + y) * w + x) * 4]);
    return t;
}

// Left half of the target samples `albedo` (separate texture + sampler), right half samples
// `detail` (combined image sampler), each at its texel centres, then `* scale + bias` from
// the uniform block.
const char* kTextured = R"(#version 450
layout(set = 0, binding = 0) uniform Params { vec4 bias; float scale; vec2 size; } params;
layout(set = 0, binding = 1) uniform texture2D albedo;
layout(set = 0, binding = 2) uniform sampler albedo_sampler;
layout(set = 0, binding = 3) uniform sampler2D detail;
layout(location = 0) out vec4 color;
void main() {
    vec2 p = gl_FragCoord.xy;
    vec4 t;
    if (p.x < params.size.x) {
        t = texture(sampler2D(albedo, albedo_sampler), p / params.size);
    } else {
        t = texture(detail, vec2(p.x - params.size.x, p.y) / params.size);
    }
    color = t * params.scale + params.bias;
}
)";

constexpr uint32_t kTexW = 12, kTexH = 10; // not powers of two, not square
const float kBias[4] = {0.25f, -0.5f, 1.0f, 2.0f};
constexpr float kScale = 2.0f;

RenderJob textured_job(TextureFilter filter) {
    RenderJob job = test::fullscreen_job(kTextured, 2 * kTexW, kTexH);
    const Reflection& fr = job.fragment_reflection;
    job.uniforms = test::block_bytes(fr, "Params");
    test::put(job.uniforms, fr, "Params", "bias", {kBias[0], kBias[1], kBias[2], kBias[3]});
    test::put(job.uniforms, fr, "Params", "scale", {kScale});
    test::put(job.uniforms, fr, "Params", "size", {float(kTexW), float(kTexH)});
    job.textures["albedo"] = make_texture(1, kTexW, kTexH, 1);
    job.textures["detail"] = make_texture(2, kTexW, kTexH, 1);
    job.filter = filter;
    job.timed_draws = 1;
    return job;
}

// Max |got - expected| over the textured image.
float textured_error(const RenderResult& r) {
    float worst = 0;
    for (uint32_t y = 0; y < kTexH; ++y) {
        for (uint32_t x = 0; x < 2 * kTexW; ++x) {
            float t[4];
            texel(x < kTexW ? 1 : 2, 0, x % kTexW, y, t);
            const float* got = &r.rgba[(size_t{y} * r.width + x) * 4];
            for (int c = 0; c < 4; ++c) {
                const float err = std::fabs(got[c] - (t[c] * kScale + kBias[c]));
                if (err > worst) {
                    worst = err;
                    UNSCOPED_INFO("worst so far: pixel (" << x << "," << y << ") channel " << c
                                                          << " got " << got[c]);
                }
            }
        }
    }
    return worst;
}

} // namespace

TEST_CASE("fullscreen shader renders exact gl_FragCoord functions", "[render]") {
    VulkanRunner& runner = test::shared_runner();

    SECTION("256x256 with timing") {
        RenderJob job = test::fullscreen_job(kFragCoord, 256, 256);
        RenderResult r = runner.render(job);
        INFO(r.error);
        REQUIRE(r.ok);
        CHECK(r.width == 256);
        CHECK(r.height == 256);
        check_fragcoord_image(r);
        CHECK(r.pipeline_ms > 0);
        CHECK(r.first_draw_ms > 0);
        REQUIRE(r.draw_ms.size() == 5);
        for (double ms : r.draw_ms)
            CHECK(ms > 0);
        CHECK(r.steady_draw_ms > 0);
        std::printf("fragcoord 256x256 on %s: pipeline %.2f ms, first draw %.2f ms, steady draw "
                    "%.3f ms (samples",
                    runner.device_info().name.c_str(), r.pipeline_ms, r.first_draw_ms,
                    r.steady_draw_ms);
        for (double ms : r.draw_ms)
            std::printf(" %.3f", ms);
        std::printf(")\n");
    }
    SECTION("non-square: rows come back top first") {
        RenderJob job = test::fullscreen_job(kFragCoord, 40, 24);
        job.timed_draws = 0;
        RenderResult r = runner.render(job);
        INFO(r.error);
        REQUIRE(r.ok);
        CHECK(r.draw_ms.empty());
        check_fragcoord_image(r);
    }
    INFO(test::joined(runner.validation_messages()));
    CHECK(runner.validation_messages().empty());
}

TEST_CASE("textures, samplers and uniforms read back exactly", "[render]") {
    VulkanRunner& runner = test::shared_runner();

    SECTION("nearest filtering at texel centres: exact") {
        RenderResult r = runner.render(textured_job(TextureFilter::Nearest));
        INFO(r.error);
        REQUIRE(r.ok);
        CHECK(textured_error(r) == 0.0f);
    }
    SECTION("linear filtering at texel centres: within 1e-4") {
        // p / size is not exact for size 12 or 10, so the bilinear weight of the neighbour
        // can be a few ulps of 1 instead of 0; neighbours differ by at most 8 here, so the
        // error stays far below 1e-4 while a wrong texel would be off by >= 0.25.
        RenderResult r = runner.render(textured_job(TextureFilter::Linear));
        INFO(r.error);
        REQUIRE(r.ok);
        CHECK(textured_error(r) <= 1e-4f);
    }
    INFO(test::joined(runner.validation_messages()));
    CHECK(runner.validation_messages().empty());
}

TEST_CASE("cube map faces are sampled in Vulkan face order", "[render]") {
    VulkanRunner& runner = test::shared_runner();
    constexpr uint32_t n = 4;
    // Pixel (x, y) of a 6n x n target looks up face x / n at texel (x % n, y). The
    // directions follow the face table of the Vulkan spec ("Cube Map Face Selection") with
    // |major axis| = 1 and sc, tc = 2 * (i + 0.5) / n - 1, all exact for n = 4.
    RenderJob job = test::fullscreen_job(R"(#version 450
layout(set = 0, binding = 0) uniform samplerCube sky;
layout(location = 0) out vec4 color;
void main() {
    const float n = 4.0;
    ivec2 p = ivec2(gl_FragCoord.xy);
    int face = p.x / int(n);
    float sc = 2.0 * (float(p.x % int(n)) + 0.5) / n - 1.0;
    float tc = 2.0 * (float(p.y) + 0.5) / n - 1.0;
    vec3 d;
    if (face == 0) d = vec3(1.0, -tc, -sc);
    else if (face == 1) d = vec3(-1.0, -tc, sc);
    else if (face == 2) d = vec3(sc, 1.0, tc);
    else if (face == 3) d = vec3(sc, -1.0, -tc);
    else if (face == 4) d = vec3(sc, -tc, 1.0);
    else d = vec3(-sc, -tc, -1.0);
    color = texture(sky, d);
}
)",
                                         6 * n, n);
    job.textures["sky"] = make_texture(3, n, n, 6);
    job.filter = TextureFilter::Nearest;
    job.timed_draws = 0;
    RenderResult r = runner.render(job);
    INFO(r.error);
    REQUIRE(r.ok);
    size_t mismatches = 0;
    for (uint32_t y = 0; y < n; ++y) {
        for (uint32_t x = 0; x < 6 * n; ++x) {
            float t[4];
            texel(3, x / n, x % n, y, t);
            const float* got = &r.rgba[(size_t{y} * r.width + x) * 4];
            for (int c = 0; c < 4; ++c)
                if (got[c] != t[c] && mismatches++ < 5)
                    UNSCOPED_INFO("pixel (" << x << "," << y << ") channel " << c << " got "
                                            << got[c] << " expected " << t[c]);
        }
    }
    CHECK(mismatches == 0);
    INFO(test::joined(runner.validation_messages()));
    CHECK(runner.validation_messages().empty());
}

TEST_CASE("jobs missing inputs fail with the binding's name", "[render]") {
    VulkanRunner& runner = test::shared_runner();

    SECTION("texture") {
        RenderJob job = textured_job(TextureFilter::Nearest);
        job.textures.erase("detail");
        RenderResult r = runner.render(job);
        CHECK_FALSE(r.ok);
        INFO(r.error);
        CHECK(r.error.find("'detail'") != std::string::npos);
        CHECK(r.rgba.empty());
    }
    SECTION("uniform block") {
        RenderJob job = textured_job(TextureFilter::Nearest);
        job.uniforms.clear();
        RenderResult r = runner.render(job);
        CHECK_FALSE(r.ok);
        INFO(r.error);
        CHECK(r.error.find("'Params'") != std::string::npos);
    }
    SECTION("a cube binding given a 2D texture") {
        RenderJob job = test::fullscreen_job(R"(#version 450
layout(set = 0, binding = 0) uniform samplerCube sky;
layout(location = 0) out vec4 color;
void main() { color = texture(sky, vec3(1.0, 0.0, 0.0)); }
)",
                                             4, 4);
        job.textures["sky"] = make_texture(0, 4, 4, 1);
        RenderResult r = runner.render(job);
        CHECK_FALSE(r.ok);
        INFO(r.error);
        CHECK(r.error.find("'sky'") != std::string::npos);
    }
    SECTION("not SPIR-V") {
        RenderJob job = test::fullscreen_job(kFragCoord, 4, 4);
        job.fragment_spirv = {1, 2, 3};
        RenderResult r = runner.render(job);
        CHECK_FALSE(r.ok);
        INFO(r.error);
        CHECK(r.error.find("fragment SPIR-V") != std::string::npos);
    }
    // Failed jobs leave the runner usable and the validation layer quiet.
    RenderResult after = runner.render(test::fullscreen_job(kFragCoord, 8, 8));
    INFO(after.error);
    CHECK(after.ok);
    INFO(test::joined(runner.validation_messages()));
    CHECK(runner.validation_messages().empty());
}

TEST_CASE("one runner, many jobs: results do not depend on order", "[render]") {
    VulkanRunner& runner = test::shared_runner();
    RenderJob fragcoord = test::fullscreen_job(kFragCoord, 32, 16);
    fragcoord.timed_draws = 0;
    RenderResult first = runner.render(fragcoord);
    RenderResult textured = runner.render(textured_job(TextureFilter::Nearest));
    RenderResult again = runner.render(fragcoord);
    REQUIRE(first.ok);
    REQUIRE(textured.ok);
    REQUIRE(again.ok);
    CHECK(first.rgba == again.rgba);
    INFO(test::joined(runner.validation_messages()));
    CHECK(runner.validation_messages().empty());
}
