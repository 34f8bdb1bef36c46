// The synthetic scene every variant is rendered over, on the GPU and on the CPU alike.
//
// World: metres, y up, water plane at y = 0 (uniform water_level), all of it moved by the
// view's world_offset (scene_views.h; what follows is the scene at offset 0). The camera and the
// sun are a view's (scene_views.h); the default, `beach`, stands at (0, 5, -7) above the beach and
// looks down the +z axis, pitched 28 degrees down, vertical field of view 60 degrees. The seabed is
// the plane y = 2 - 0.25 (z + 12): dry beach for z < -4, the shoreline at z = -4, 10 m deep at
// z = 36 and deeper beyond. A sphere of radius 1 m at (1.5, -1.3, 3) sits half buried in the
// seabed, its top 0.3 m under the surface; a view may stand another sphere out of the water
// (the `reflection` view does). Rays that hit nothing see a smooth sky gradient; their
// "position" is 1000 m along the ray (above the water, so the water pass leaves them alone).
// Sand and spheres are lit by the sun (Lambert + ambient); sand carries a smooth, band-limited
// ripple pattern (wavelengths >= 2 m) so the image is not flat but no texel is noise: outputs
// must not be hypersensitive to sub-texel differences between GPU and CPU.
//
// Every texture is made at the render resolution, so the fullscreen pass samples texel
// centres and linear filtering returns texels unchanged (exactly so for power-of-two sizes,
// where the pixel-centre uv is exact in float; other sizes blend neighbours by ~1e-7).
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "watergen/caustics/caustics_pass.h"
#include "watergen/eval/scene/scene_views.h"
#include "watergen/headless/texture_data.h"
#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/water/presets.h"

namespace watergen {

struct SyntheticScene {
    uint32_t width = 0, height = 0;
    std::map<std::string, TextureData> textures; // by binding name (scene_color, scene_position)
    std::map<std::string, std::vector<double>> uniforms; // camera, sun: override parameter defaults
    SceneView view = beach_view(); // the camera, sun and standing sphere the textures were made for
    // The eye scene_position's texels are relative to (xyz = scene point - this, in m, as an
    // engine with a large world writes them): eye_position as the texels were last made.
    std::array<double, 3> position_eye{};

    // CPU views of the same textures for the evaluator.
    EvalInputs eval_inputs() const;
};

// CPU evaluator views of runner textures (the map must outlive the views).
std::map<std::string, TextureView>
texture_views(const std::map<std::string, TextureData>& textures);

// Deterministic: the same size and view always yield the same bytes. Without a view: `beach`,
// byte for byte the scene every render used before views existed.
SyntheticScene make_synthetic_scene(uint32_t width, uint32_t height);
SyntheticScene make_synthetic_scene(uint32_t width, uint32_t height, const SceneView& view);

// The scene at width x height seen from the view named `view` (beach for a name that is none),
// moved by `world_offset` (SceneView::world_offset), its uniforms following the preset if any:
// a preset's values, its sun_direction among them, replace the view's (a position among them
// moved by the offset, placed_scene_value). What the commands draw a variant named by flags
// over.
SyntheticScene preset_scene(uint32_t width, uint32_t height, const Preset* preset,
                            const std::string& view = "beach",
                            const std::array<double, 3>& world_offset = {});

// A value of one of the scene's position parameters given in the scene's own frame (around
// the origin) moved by the world offset: eye_position + offset, water_level + offset y, the
// x0, z0 of caustics_window and fourier_map_origin + offset x, z. Any other parameter's value
// (and every value at offset 0) is returned as it is. The scene's own values go through it, and
// so do render --set's.
std::vector<double> placed_scene_value(const std::string& name, std::vector<double> value,
                                       const std::array<double, 3>& world_offset);

// Re-expresses scene_position's texels relative to the scene's eye_position uniform when it
// moved from position_eye (render --set, a conformed scene): the scene stays where it stood
// and the eye moves over it. A sky texel keeps its direction and distance from the new eye.
// True when the texels moved (their depth buffer is then to be made again).
bool follow_scene_eye(SyntheticScene& scene);

// Inputs of the node families, each in its own file under render/: textures and uniforms the
// nodes of those axes read (their binding names are the TextureInput names the nodes declare),
// made for scene.view.
void add_foam_inputs(SyntheticScene& scene);   // scene_foam_inputs.cpp
void add_optics_inputs(SyntheticScene& scene); // scene_optics_inputs.cpp: reflection, refraction
void add_wave_inputs(SyntheticScene& scene);   // scene_wave_inputs.cpp: waves, normals
// scene_depth_inputs.cpp: scene_depth, the window depth of scene_position's texels under the
// depth conventions in scene.uniforms (scene_input.h; their defaults otherwise), and the
// inverse view-projection uniforms. Made again whenever scene_position or a convention changes.
void add_depth_inputs(SyntheticScene& scene);
// scene_caustics_inputs.cpp: caustics_tile and caustics_map from the CPU photon reference
// (caustics_reference.h); needs the scene's sun_direction and time uniforms.
void add_caustics_inputs(SyntheticScene& scene);

// A sky texel's position lies this far along its ray (its scene_position alpha, the distance);
// the depth buffer's planes: near for both Z conventions, far for the standard one (the reversed
// projection's far plane is at infinity).
inline constexpr double kSceneSkyDistance = 1000.0;
inline constexpr double kSceneNear = 0.1, kSceneFar = 2000.0;

// The caustics map's setting, shared by the CPU-made map and the pass drawn for a scene
// (scene_caustics_pass.h): the bottom 2 m under the water level (the seabed in the default
// window lies 0 to 2.25 m deep); photons (the pass's grid) over the window grown by
// caustics_margin() (3.4 m), as light enters from beside it; 64 texels per side, the nodes'
// caustics_map_texels default.
inline constexpr double kSceneCausticsDepth = 2.0;
inline constexpr double kSceneCausticsMargin = caustics_margin(kSceneCausticsDepth);
inline constexpr uint32_t kSceneCausticsTexels = 64;

// A caustics texture from intensities (texels x texels, row-major, row = z): r = g = b = the
// intensity, a = 1, the layout caustics_tile and caustics_map share.
TextureData caustics_texture(const std::vector<double>& intensity, uint32_t texels);

// The camera of a view (nodes that project world points to the screen read its matrices,
// scene_optics_inputs.cpp); without a view, the beach camera. Its eye is in the world: the
// view's eye moved by the view's world_offset.
struct SceneCamera {
    double eye[3];
    double forward[3], right[3], up[3]; // unit; right x up = forward
    double tan_half_fov_y, aspect;
};
SceneCamera scene_camera(const SceneView& view, uint32_t width, uint32_t height);
SceneCamera scene_camera(uint32_t width, uint32_t height);

} // namespace watergen
