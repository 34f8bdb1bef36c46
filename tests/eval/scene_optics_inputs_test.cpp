// The synthetic scene's reflection / refraction inputs (render/scene_optics_inputs.cpp):
// shapes, determinism, and consistency between the planar reflection map, its matrices and
// the sky cube, and the direction conventions of the Fourier coefficients.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "reflection_support.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/runtime/host_values.h"
#include "watergen/water/axis_registry.h"
#include "watergen/water/surface.h"
#include "watergen/water/water_shader.h"

using namespace watergen;

TEST_CASE("optics_inputs_have_their_documented_shapes_and_are_deterministic", "[scene]") {
    const SyntheticScene a = make_synthetic_scene(40, 24), b = make_synthetic_scene(40, 24);
    struct Shape {
        const char* name;
        uint32_t width, height, layers;
    };
    for (const Shape& s :
         {Shape{"sky_cube", 32, 32, 6}, Shape{"reflection_map", 40, 24, 1},
          Shape{"fourier_coefs1", 16, 16, 1}, Shape{"fourier_coefs2", 16, 16, 1}}) {
        INFO(s.name);
        REQUIRE(a.textures.count(s.name) == 1);
        const TextureData& t = a.textures.at(s.name);
        CHECK(t.width == s.width);
        CHECK(t.height == s.height);
        CHECK(t.layers == s.layers);
        REQUIRE(t.rgba.size() == size_t(s.width) * s.height * s.layers * 4);
        for (float v : t.rgba)
            CHECK(std::isfinite(v));
        CHECK(t.rgba == b.textures.at(s.name).rgba);
    }
    for (const char* prefix : {"reflection", "refraction"})
        for (int k = 0; k < 4; ++k) {
            const std::string name = std::string(prefix) + "_view_proj_c" + std::to_string(k);
            REQUIRE(a.uniforms.count(name) == 1);
            CHECK(a.uniforms.at(name).size() == 4);
            CHECK(a.uniforms.at(name) == b.uniforms.at(name));
        }
}

TEST_CASE("planar_reflection_map_agrees_with_the_sky_cube_along_the_mirrored_ray", "[scene]") {
    // Both are made from one sky: over open water (nothing above it in this scene), the planar
    // map looked up with the mirrored camera's matrix and 002's FOV extension must show the
    // sky the cube shows along reflect(-V, N). A flipped axis, a wrong FOV factor or an
    // unmirrored camera would look up the sky 10s of degrees away (differences ~0.1-0.5).
    const uint32_t w = 64, h = 64;
    const SyntheticScene scene = make_synthetic_scene(w, h);
    const SceneCamera cam = scene_camera(w, h);
    const FrameCentre centre = frame_centre_of(cam.eye[0], cam.eye[2]);
    std::vector<double> rays, points;
    for (double u : {0.1, 0.3, 0.5, 0.7, 0.9})
        for (double v : {0.5, 0.6, 0.75, 0.9}) {
            const double sx = (2 * u - 1) * cam.tan_half_fov_y * cam.aspect,
                         sy = (1 - 2 * v) * cam.tan_half_fov_y;
            double d[3], len = 0;
            for (int k = 0; k < 3; ++k) {
                d[k] = cam.forward[k] + cam.right[k] * sx + cam.up[k] * sy;
                len += d[k] * d[k];
            }
            len = std::sqrt(len);
            const double t = -cam.eye[1] / (d[1] / len);
            // The graph reads the point in the shader's frame (host_values.h).
            const double frame[3] = {centre.x, 0.0, centre.z};
            for (int k = 0; k < 3; ++k) {
                rays.push_back(d[k] / len);
                points.push_back(cam.eye[k] + d[k] / len * t - frame[k]);
            }
        }
    Graph g;
    Surface planar(g), cube(g);
    for (Surface* s : {&planar, &cube}) {
        s->view_ray = varying(g, "view_ray", Type::Vec3);
        s->surface_point = varying(g, "surface_point", Type::Vec3);
        s->normal = constant(g, {0.0, 1.0, 0.0});
    }
    compose_choice(planar, "reflection", "planar_projective");
    compose_choice(cube, "reflection", "sky_cubemap");
    g.set_output("planar", planar.reflected.id());
    g.set_output("cube", cube.reflected.id());
    EvalInputs in = scene.eval_inputs();
    in.varyings["view_ray"] = rays;
    in.varyings["surface_point"] = points;
    in.lanes = rays.size() / 3;
    const EvalResult p = evaluate(g, "planar", in, EvalPrecision::Double);
    const EvalResult c = evaluate(g, "cube", in, EvalPrecision::Double);
    REQUIRE(p.ok());
    REQUIRE(c.ok());
    double worst = 0;
    for (size_t i = 0; i < p.values.size(); ++i)
        worst = std::max(worst, std::fabs(p.values[i] - c.values[i]));
    // Measured 3.4e-4: bilinear filtering of a 32-texel face (2.8 degrees a texel) against a
    // map at 64 px over a 1.5x wider view.
    CHECK(worst < 2e-3);
}

TEST_CASE("fourier_coefficients_put_the_beach_behind_and_the_ridge_ahead", "[scene]") {
    // The maps encode the horizon tangent: towards -z the beach rises at the seabed's slope
    // 0.25 (its Fourier truncation a little below), towards +z the ridge 300 m away, 25 +- 10 m
    // high; sideways, along the shore, the horizon is lower than behind. Swapped coefficient
    // slots (a <-> b) would swap these directions.
    const SyntheticScene scene = make_synthetic_scene(16, 16);
    const TextureData& c1 = scene.textures.at("fourier_coefs1");
    const TextureData& c2 = scene.textures.at("fourier_coefs2");
    for (size_t texel : {size_t{0}, size_t{7 * 16 + 8}, size_t{255}}) {
        INFO("texel " << texel);
        std::vector<double> tuples;
        for (const auto& ray : {std::vector<double>{0, 0, -1}, {0, 0, 1}, {1, 0, 0}}) {
            for (int k = 0; k < 4; ++k)
                tuples.push_back(c1.rgba[texel * 4 + static_cast<size_t>(k)]);
            for (int k = 0; k < 4; ++k)
                tuples.push_back(c2.rgba[texel * 4 + static_cast<size_t>(k)]);
            tuples.insert(tuples.end(), ray.begin(), ray.end());
        }
        const auto r = test::eval_catalog("reflection.fourier_series", tuples);
        CHECK(r.at(0) > 0.17);
        CHECK(r.at(0) < 0.26);
        CHECK(r.at(1) > 0.02);
        CHECK(r.at(1) < 0.16);
        CHECK(r.at(2) < r.at(0));
    }
}

TEST_CASE("half_precision_variants_stay_finite_and_close_to_float", "[scene][precision]") {
    // precision=half rounds the shading to binary16 but keeps positions and projections in
    // float (the skeleton's rule): the image stays within half's few 1e-3 of the float one
    // (measured 1.4e-3, 4.3e-3, 3.3e-3 for the three cases).
    const SyntheticScene scene = make_synthetic_scene(64, 64);
    for (const char* choices : {"reflection=sky_cubemap,refraction=none",
                                "reflection=planar_projective,refraction=refracted_ray",
                                "reflection=fourier_horizon,refraction=screen_distort"}) {
        INFO(choices);
        std::string error;
        const auto v = parse_variant_key(
            std::string("precision=half,specular=none,foam=none,") + choices, &error);
        REQUIRE(v.has_value());
        const WaterShader shader = build_water_shader(*v);
        const EvalResult f = evaluate_image(shader.fragment, "color", scene.eval_inputs(), 64, 64,
                                            EvalPrecision::Float);
        const EvalResult h = evaluate_image(shader.fragment, "color", scene.eval_inputs(), 64, 64,
                                            EvalPrecision::Half);
        REQUIRE(f.ok());
        REQUIRE(h.ok());
        double worst = 0;
        for (size_t i = 0; i < f.values.size(); ++i) {
            REQUIRE(std::isfinite(h.values[i]));
            worst = std::max(worst, std::fabs(h.values[i] - f.values[i]));
        }
        std::printf("%s precision=half: max |half - float| %.3g\n", choices, worst);
        CHECK(worst < 1e-2);
    }
}
