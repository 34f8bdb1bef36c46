#include "watergen/water/water_shader.h"

#include <optional>

#include "watergen/water/axis_registry.h"

#include "watergen/water/nodes.h"
#include "watergen/water/presets.h"
#include "watergen/water/scene_quantities.h"
#include "watergen/water/surface.h"

namespace watergen {

TextureInput scene_color_texture() {
    return {"scene_color", Type::Texture2D, "lit colour of the scene under the water, linear rgb",
            ""};
}

TextureInput scene_position_texture() {
    return {"scene_position", Type::Texture2D, "scene surface position less the eye, xyz in m", ""};
}

namespace {

// The axis' offered choice, or a switch between several.
void compose_axis(Surface& s, const ShaderChoices& choices, const std::string& axis) {
    const std::vector<std::string>& offered = choices.offered(axis);
    if (offered.size() == 1)
        compose_choice(s, axis, offered.front());
    else
        compose_switch(s, axis, offered, choices.mode == BuildMode::Specialized);
}

// An error for choices no shader can compose: an axis without a choice, several choices on a
// permutation-only axis (or in Permutations mode).
void check_choices(Graph& g, const ShaderChoices& choices) {
    if (choices.choices.size() != axes().size()) {
        g.error("shader choices: " + std::to_string(choices.choices.size()) + " axes, expected " +
                std::to_string(axes().size()));
        return;
    }
    for (size_t i = 0; i < axes().size(); ++i) {
        const std::string& axis = axes()[i].name;
        const size_t n = choices.choices[i].size();
        if (n == 0) g.error(axis + ": no choice offered");
        if (n > 1 && (permutation_only(axis) || choices.mode == BuildMode::Permutations))
            g.error(axis + ": one choice per shader " +
                    (permutation_only(axis) ? std::string("(a permutation-only axis)")
                                            : std::string("in permutations mode")));
    }
}

} // namespace

WaterShader build_water_shader(const Variant& variant, const Preset* preset, SurfaceSearch search) {
    return build_water_shader(ShaderChoices::of(variant), preset, search);
}

WaterShader build_water_shader(const ShaderChoices& choices, const Preset* preset,
                               SurfaceSearch search) {
    WaterShader shader{choices.first_variant(), preset ? preset->name : "", Graph{}, std::nullopt};
    if (choices.mode != BuildMode::Permutations) shader.switched = choices;
    Graph& g = shader.fragment;
    check_choices(g, choices);
    if (has_errors(g.diagnostics())) return shader;
    Surface s(g);
    // What the fragment stage is given: the screen pass' uv, or a mesh's rasterised point
    // (nodes/geometry.cpp).
    compose_axis(s, choices, "geometry");
    {
        OriginScope scope(g, "surface");
        s.scene_rgb = named(sample(texture(g, scene_color_texture()), s.uv).xyz(), "scene_rgb");
        // One definition each for every stage (mesh_shader.h): one block serves them all.
        s.eye = scene_eye_position(g);
        s.level = scene_water_level(g);
        s.time = scene_time(g);
        s.sun_travel = scene_sun_direction(g);
        s.sun_color = uniform(g, {.name = "sun_color",
                                  .type = Type::Vec3,
                                  .default_value = {1.0, 0.95, 0.85},
                                  .max = 1e3,
                                  .seed = "000"});
    }
    // Where the scene lies behind the pixel: a texture or the depth buffer (nodes/scene_input).
    compose_axis(s, choices, "scene_input");
    {
        OriginScope scope(g, "surface");
        s.scene_distance = named(length(s.to_scene), "scene_distance");
        s.view_ray = named(s.to_scene / max(s.scene_distance, 1e-6), "view_ray");
    }
    const bool relaxed = choices.offered("precision").front() == "half";
    // Geometry (positions, times, wave phases) stays 32-bit: half cannot hold 1e5 m or a day
    // of seconds. The precision axis relaxes the shading math only: everything composed after
    // the normals (composition_order(): waves, normals, refraction, caustics, extinction,
    // reflection, fresnel, specular, foam, shore, with a project's axes where they asked).
    // Caustics light the bottom the refraction sees, before the water column dims it.
    std::optional<RelaxedScope> shading;
    bool surface_done = false;
    for (const std::string& axis : composition_order()) {
        if (surface_done && !shading) shading.emplace(g, relaxed);
        if (axis == "waves" && search == SurfaceSearch::Converged &&
            choices.offered(axis).size() == 1)
            compose_converged_waves(s, choices.offered(axis).front());
        else
            compose_axis(s, choices, axis);
        if (axis == "normals") {
            OriginScope scope(g, "surface");
            s.to_eye = -s.view_ray;
            s.n_dot_v = named(dot(s.normal, s.to_eye), "n_dot_v");
            surface_done = true;
        } else if (axis == "specular") {
            OriginScope scope(g, "compose");
            s.color = named(mix(s.water_color, s.reflected, s.fresnel) + s.specular, "water_rgb");
        }
    }
    OriginScope scope(g, "compose");
    if (has_errors(g.diagnostics())) return shader;
    Expr rgb = select(s.is_water, s.color, s.scene_rgb);
    g.set_output("color", vec4(rgb, constant(g, 1.0)).id());
    if (const std::string& geometry = choices.offered("geometry").front();
        geometry != "screen_pass") {
        const std::vector<std::string>& waves = choices.offered("waves");
        if (waves.size() != 1)
            g.error("geometry=" + geometry +
                    ": the grid is displaced by one wave model; offer one waves choice per shader");
        else
            shader.mesh = build_mesh_stages(geometry, waves.front());
    }
    if (preset) {
        std::vector<Graph*> graphs = {&g};
        if (shader.mesh)
            for (Graph* stage : shader.mesh->graphs())
                graphs.push_back(stage);
        for (Graph* graph : graphs)
            for (const auto& name : apply_preset(*graph, *preset))
                g.error("preset '" + preset->name + "': parameter '" + name + "' has another size");
    }
    return shader;
}

} // namespace watergen
