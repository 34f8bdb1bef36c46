// The depth buffer of the synthetic scene, for the depth_buffer scene input
// (water/nodes/scene_input.h): what the scene pass of an engine with the scene's camera and the
// conventions in the scene's uniforms would have written, and the inverse view-projection the
// water pass unprojects it with. Made from the scene_position texture, so a scene conformed to a
// scene's facts (scene_conform.cpp) gets the depth of its moved texels.
#include <glm/glm.hpp>

#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/water/nodes/scene_input.h"

namespace watergen {

namespace {

using glm::dmat4;
using glm::dvec3;
using glm::dvec4;

// A 0/1 convention: the scene's value, else the parameter's default.
bool convention(const SyntheticScene& scene, const Parameter& p) {
    auto it = scene.uniforms.find(p.name);
    const double v =
        it != scene.uniforms.end() && it->second.size() == 1 ? it->second[0] : p.default_value[0];
    return v > 0.5;
}

struct Conventions {
    bool reversed, gl_range, y_up, camera_relative;
};

// World (or eye-relative) to view: x right, y up, z forward (the distance in front).
dmat4 view_matrix(const SceneCamera& c, const dvec3& eye, bool camera_relative) {
    const dvec3 right{c.right[0], c.right[1], c.right[2]}, up{c.up[0], c.up[1], c.up[2]},
        forward{c.forward[0], c.forward[1], c.forward[2]};
    const dvec3 at = camera_relative ? dvec3{0.0} : eye;
    dmat4 v(1.0);
    for (int k = 0; k < 3; ++k) {
        v[k][0] = right[k];
        v[k][1] = up[k];
        v[k][2] = forward[k];
    }
    v[3] = dvec4{-glm::dot(right, at), -glm::dot(up, at), -glm::dot(forward, at), 1.0};
    return v;
}

// View to clip. Reversed Z with an infinite far plane (what reversed-Z engines use); standard Z
// with a far plane beyond the sky. NDC y follows the convention (Vulkan's points down).
dmat4 projection(const SceneCamera& c, const Conventions& k) {
    const double n = kSceneNear, f = kSceneFar;
    dmat4 p(0.0);
    p[0][0] = 1.0 / (c.tan_half_fov_y * c.aspect);
    p[1][1] = (k.y_up ? 1.0 : -1.0) / c.tan_half_fov_y;
    p[2][3] = 1.0; // w = z
    if (k.reversed && !k.gl_range) {
        p[3][2] = n; // ndc z = n / z: 1 at the near plane, 0 at infinity
    } else if (k.reversed) {
        p[2][2] = -1.0; // ndc z = 2 n / z - 1
        p[3][2] = 2.0 * n;
    } else if (!k.gl_range) {
        p[2][2] = f / (f - n); // ndc z = f / (f - n) (1 - n / z)
        p[3][2] = -f * n / (f - n);
    } else {
        p[2][2] = (f + n) / (f - n); // OpenGL's
        p[3][2] = -2.0 * f * n / (f - n);
    }
    return p;
}

} // namespace

void add_depth_inputs(SyntheticScene& scene) {
    auto position = scene.textures.find("scene_position");
    if (position == scene.textures.end()) return;
    const Conventions k{
        convention(scene, scene_depth_reversed()), convention(scene, scene_depth_gl_range()),
        convention(scene, scene_ndc_y_up()), convention(scene, scene_camera_relative())};
    const SceneCamera cam = scene_camera(scene.view, scene.width, scene.height);
    dvec3 eye{cam.eye[0], cam.eye[1], cam.eye[2]};
    if (auto it = scene.uniforms.find("eye_position");
        it != scene.uniforms.end() && it->second.size() == 3)
        eye = {it->second[0], it->second[1], it->second[2]};
    const dmat4 view_proj = projection(cam, k) * view_matrix(cam, eye, k.camera_relative);

    // The texels are relative to position_eye (follow_scene_eye): world = it + texel.
    const dvec3 at{scene.position_eye[0], scene.position_eye[1], scene.position_eye[2]};
    const TextureData& from = position->second;
    TextureData depth{from.width, from.height, 1, std::vector<float>(from.rgba.size(), 0.0f)};
    const double far_depth = k.reversed ? 0.0 : 1.0;
    for (size_t i = 0; i + 3 < from.rgba.size(); i += 4) {
        double window = far_depth; // the clear value: nothing drawn here
        if (from.rgba[i + 3] < kSceneSkyDistance) {
            const dvec3 texel{from.rgba[i], from.rgba[i + 1], from.rgba[i + 2]};
            const dvec3 p = k.camera_relative ? texel + (at - eye) : at + texel;
            const dvec4 q = view_proj * dvec4(p, 1.0);
            const double ndc_z = q.z / q.w;
            window = k.gl_range ? 0.5 * ndc_z + 0.5 : ndc_z;
        }
        depth.rgba[i] = static_cast<float>(window);
        depth.rgba[i + 3] = 1.0f;
    }
    scene.textures["scene_depth"] = std::move(depth);
    const dmat4 inverse = glm::inverse(view_proj);
    for (int c = 0; c < 4; ++c)
        scene.uniforms[scene_inv_view_proj_column(c).name] = {inverse[c][0], inverse[c][1],
                                                              inverse[c][2], inverse[c][3]};
}

} // namespace watergen
