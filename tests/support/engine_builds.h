// Builds of the example material written to temporary directories once per test binary, for the
// tests of the engine runtime library (watergen::runtime) that open them as an engine would.
#pragma once

#include "build_test_support.h"
#include "watergen/pipeline/build/build_output.h"
#include "watergen/plan/material.h"
#include "watergen/runtime/shader_build.h"

#include <memory>

namespace watergen::test {

// `watergen build examples/materials/default.json [--scene examples/scenes/*.json]` into a
// fresh directory; REQUIREs success.
inline const std::filesystem::path& example_build(bool with_scenes) {
    static TempDir unpruned("engine-unpruned"), scenes("engine-scenes");
    static bool built[2] = {false, false};
    TempDir& dir = with_scenes ? scenes : unpruned;
    if (!built[with_scenes]) {
        Diagnostics ds;
        auto material = load_material(source_dir() + "/examples/materials/default.json", ds);
        REQUIRE(material);
        BuildRequest request; // field by field: GCC 12 warns on the aggregate form
        request.material = *material;
        if (with_scenes) request.scenes = example_scenes();
        request.out = dir.path / "out";
        const BuildSummary s = build_material(request);
        REQUIRE(s.ok());
        built[with_scenes] = true;
    }
    static const std::filesystem::path out[2] = {unpruned.path / "out", scenes.path / "out"};
    return out[with_scenes];
}

// The example material for open_ocean in a specialized (frozen too) or branching build.
inline ShaderBuild open_mode_build(BuildMode mode) {
    static std::map<BuildMode, std::unique_ptr<TempDir>> dirs;
    auto& dir = dirs[mode];
    if (!dir) {
        dir = std::make_unique<TempDir>(std::string("engine-") + to_string(mode));
        Diagnostics ds;
        auto material = load_material(source_dir() + "/examples/materials/default.json", ds);
        REQUIRE(material);
        BuildRequest request;
        request.material = *material;
        for (const SceneFacts& s : example_scenes())
            if (s.name == "open_ocean") request.scenes.push_back(s);
        request.out = dir->path / "out";
        request.mode = mode;
        request.freeze = mode == BuildMode::Specialized;
        REQUIRE(build_material(request).ok());
    }
    std::string error;
    auto b = ShaderBuild::open(dir->path / "out", &error);
    INFO(error);
    REQUIRE(b);
    return *b;
}

// Gerstner waves with caustics none, area_ratio and photon_splat (3 variants, 2 passes),
// unpruned; built once per test binary.
inline Material caustics_material() {
    Diagnostics ds;
    auto m = MaterialBuilder("caustics")
                 .offer("waves", {"gerstner"})
                 .offer("caustics", {"none", "area_ratio", "photon_splat"})
                 .build(ds);
    REQUIRE(m);
    return *m;
}

inline const std::filesystem::path& caustics_build() {
    static TempDir dir("engine-caustics");
    static bool built = false;
    if (!built) {
        BuildRequest request;
        request.material = caustics_material();
        request.out = dir.path / "out";
        REQUIRE(build_material(request).ok());
        built = true;
    }
    static const std::filesystem::path out = dir.path / "out";
    return out;
}

inline ShaderBuild open_example_build(bool with_scenes) {
    std::string error;
    auto b = ShaderBuild::open(example_build(with_scenes), &error);
    INFO(error);
    REQUIRE(b);
    return *b;
}

} // namespace watergen::test
