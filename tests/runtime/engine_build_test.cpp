// The engine runtime library on real builds of the example material: opening a build (and the
// errors of a missing or corrupt manifest), selecting variants (exact, partial, pruned, nearest
// kept, runtime key), the bytes of its files, and the uniform writer's checks (unknown name,
// wrong type, parameters the scene folded or removed).
#include <catch2/catch.hpp>

#include <fstream>

#include "engine_builds.h"
#include "watergen/runtime/uniform_writer.h"

using namespace watergen;

namespace {

void write(const std::filesystem::path& p, const std::string& text) {
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
}

std::string open_error(const std::filesystem::path& dir) {
    std::string error;
    CHECK_FALSE(ShaderBuild::open(dir, &error));
    return error;
}

} // namespace

TEST_CASE("opening a build names the manifest file and the JSON key that is wrong") {
    test::TempDir dir("engine-open");
    CHECK_THAT(open_error(dir.path / "none"), Catch::Contains("none/manifest.json: no such file"));
    write(dir.path / "a/manifest.json", "{\"generator\": \"watergen 0.1.0\", ");
    CHECK_THAT(open_error(dir.path / "a"), Catch::Contains("a/manifest.json: not a JSON object"));
    write(dir.path / "b/manifest.json", "{\"generator\": \"other 1\"}");
    CHECK_THAT(open_error(dir.path / "b"),
               Catch::Contains("b/manifest.json: generator: 'other 1'; expected"));
    // A real manifest with one key broken.
    std::string manifest = test::read_file(test::example_build(true) / "manifest.json");
    const std::string files = "\"files\": {";
    const size_t at = manifest.find(files);
    REQUIRE(at != std::string::npos);
    manifest.replace(at, files.size(), "\"files\": 7, \"x\": {");
    write(dir.path / "c/manifest.json", manifest);
    CHECK_THAT(open_error(dir.path / "c"),
               Catch::Contains("c/manifest.json: variants[0].files: expected an object"));
}

TEST_CASE("a build lists its variants and selects by choices, scene and runtime key") {
    const ShaderBuild b = test::open_example_build(true);
    CHECK(b.scenes() == std::vector<std::string>{"harbour_night", "mountain_lake", "open_ocean"});
    CHECK(b.variants().size() == 56);
    CHECK(b.axes().at("foam") == std::vector<std::string>{"none", "shore"});
    const BuildVariant& first = b.variants()[0];

    // Exact, by every axis.
    Selection s = b.select(first.scene, first.choices);
    REQUIRE(s.ok());
    CHECK(s.variant == &first);
    // By runtime key: the key string and the short hash.
    CHECK(b.select_key(first.scene, first.key).variant == &first);
    CHECK(b.select_key(first.scene, first.hash).variant == &first);

    // Partial: several match, the error names the axes left open.
    s = b.select("open_ocean", {{"fresnel", "schlick"}});
    CHECK_FALSE(s.ok());
    CHECK_THAT(s.error, Catch::Contains("8 variants of scene open_ocean match; name a choice for "
                                        "shore, specular, waves"));
    s = b.select(
        "open_ocean",
        {{"fresnel", "schlick"}, {"specular", "none"}, {"waves", "flat"}, {"shore", "hard"}});
    REQUIRE(s.ok());
    CHECK(s.variant->key == "fresnel=schlick,extinction=absorb_scatter,specular=none,foam=none,"
                            "reflection=sky_cubemap,refraction=screen_distort,normals=flat,"
                            "waves=flat,shore=hard,precision=full,caustics=none");

    // Pruned: open_ocean keeps no shore foam. Error by default, naming what is missing.
    const std::map<std::string, std::string> wanted = {{"fresnel", "schlick"},
                                                       {"specular", "none"},
                                                       {"waves", "flat"},
                                                       {"shore", "hard"},
                                                       {"foam", "shore"}};
    s = b.select("open_ocean", wanted);
    CHECK_FALSE(s.ok());
    CHECK_THAT(s.error, Catch::Contains("scene open_ocean pruned every variant with foam=shore"));
    // Nearest kept: says what it changed.
    s = b.select("open_ocean", wanted, Fallback::NearestKept);
    REQUIRE(s.ok());
    CHECK(s.changed == std::vector<std::string>{"foam: shore -> none"});
    CHECK(s.variant->choices.at("foam") == "none");
    CHECK(s.variant->choices.at("fresnel") == "schlick");

    // Unknown axis, choice and scene are errors even with NearestKept.
    CHECK_THAT(b.select("open_ocean", {{"foo", "x"}}, Fallback::NearestKept).error,
               Catch::Contains("no axis 'foo' in the material"));
    CHECK_THAT(b.select("open_ocean", {{"foam", "lots"}}, Fallback::NearestKept).error,
               Catch::Contains("axis foam has no choice 'lots'"));
    CHECK_THAT(b.select("", {{"foam", "none"}}).error, Catch::Contains("no scene ''"));
    CHECK_THAT(b.select_key("open_ocean", "fresnel").error,
               Catch::Contains("'fresnel' is not axis=choice"));
}

TEST_CASE("a variant's files come out byte for byte, and a target the scene did not build is an "
          "error") {
    const ShaderBuild b = test::open_example_build(true);
    const Selection s = b.select(
        "open_ocean",
        {{"fresnel", "schlick"}, {"specular", "none"}, {"waves", "flat"}, {"shore", "hard"}});
    REQUIRE(s.ok());
    const BuildVariant& v = *s.variant;
    std::string error;
    for (const char* lang : {"glsl", "hlsl"})
        for (ShaderStage stage : {ShaderStage::Vertex, ShaderStage::Fragment}) {
            const auto words = b.spirv(v, lang, stage, &error);
            INFO(error);
            REQUIRE(words);
            CHECK((*words)[0] == 0x07230203u); // the SPIR-V magic number
            const std::string disk =
                test::read_file(b.directory() / v.shader_directory / lang /
                                (std::string("water.") + stage_tag(stage) + ".opt.spv"));
            CHECK(disk.size() == words->size() * 4);
            CHECK(std::memcmp(disk.data(), words->data(), disk.size()) == 0);
            const auto r = b.reflection(v, lang, stage, &error);
            REQUIRE(r);
            CHECK(r->stage == stage);
        }
    const auto msl = b.source(v, "msl", ShaderStage::Fragment, &error);
    REQUIRE(msl);
    CHECK_THAT(*msl, Catch::Contains("fragment"));
    // open_ocean's targets have no glsl330.
    CHECK_FALSE(b.source(v, "glsl330", ShaderStage::Fragment, &error));
    CHECK_THAT(error, Catch::Contains("the build has no glsl330 file"));
    CHECK_FALSE(b.read("../manifest.json", &error));
    CHECK_THAT(error, Catch::Contains("expected a path inside the build directory"));
    CHECK_FALSE(b.read("open_ocean/nothing.spv", &error));
    CHECK_THAT(error, Catch::Contains("does not list 'open_ocean/nothing.spv'"));
}

TEST_CASE("the uniform writer names the parameter and the types, and says what folding did") {
    const ShaderBuild b = test::open_example_build(true);
    const Selection s = b.select("harbour_night", {{"fresnel", "exact"},
                                                   {"specular", "none"},
                                                   {"foam", "none"},
                                                   {"waves", "flat"},
                                                   {"shore", "hard"}});
    REQUIRE(s.ok());
    UniformWriter w(*s.variant);
    REQUIRE(w.set("eye_position", {0.0f, 5.0f, -2.0f}).ok);
    REQUIRE(w.value("eye_position"));
    CHECK(*w.value("eye_position") == std::vector<float>{0.0f, 5.0f, -2.0f});

    Write r = w.set("eye_position", 1.0f);
    CHECK_FALSE(r.ok);
    CHECK(r.error == "parameter 'eye_position' is vec3; given float");
    // Outside the declared range: refused, naming the component and the range; the shader was
    // folded and bounded for values inside it. The bound itself is inside.
    r = w.set("eye_position", {2e7f, 5.0f, -2.0f});
    CHECK_FALSE(r.ok);
    CHECK(r.error ==
          "parameter 'eye_position' (vec3): value 0, 2e+07, is outside its range [-1e+07, 1e+07]");
    CHECK(w.set("eye_position", {1e7f, 5.0f, -1e7f}).ok);
    CHECK(*w.value("eye_position") == std::vector<float>{1e7f, 5.0f, -1e7f});
    REQUIRE(w.set("eye_position", {0.0f, 5.0f, -2.0f}).ok);
    r = w.set("no_such_thing", {1.0f, 2.0f});
    CHECK_FALSE(r.ok);
    CHECK_THAT(r.error, Catch::StartsWith("unknown parameter 'no_such_thing' (given vec2): "
                                          "variant fresnel=exact,"));
    // Folded by the scene (water_level = 0): the same value is a reported no-op, another an error.
    r = w.set("water_level", 0.0f);
    CHECK(r.ok);
    CHECK(r.note == "parameter 'water_level' was folded to 0 by scene harbour_night; the same "
                    "value is a no-op");
    r = w.set("water_level", 0.5f);
    CHECK_FALSE(r.ok);
    CHECK_THAT(r.error, Catch::StartsWith("parameter 'water_level' was folded to 0 by scene "
                                          "harbour_night"));
    CHECK_THAT(r.error, Catch::Contains("the shader cannot take 0.5"));
    // Removed without a value (its term is gone): a reported no-op.
    r = w.set("reflection_distortion", 0.25f);
    CHECK(r.ok);
    CHECK_THAT(r.note, Catch::Contains("is not read by variant"));
}

TEST_CASE("specialized and branching builds select the same way and carry the selector values") {
    const std::map<std::string, std::string> wanted = {{"fresnel", "exact"},
                                                       {"specular", "blinn_phong"},
                                                       {"waves", "gerstner"},
                                                       {"shore", "soft"}};
    std::string error;

    const ShaderBuild spec = test::open_mode_build(BuildMode::Specialized);
    CHECK(spec.mode() == "specialized");
    CHECK(spec.variants().size() == 16); // 400 m deep: no caustics

    Selection s = spec.select("open_ocean", wanted);
    INFO(s.error);
    REQUIRE(s.ok());
    // One shader serves every variant: four selectors as specialization constants, set to this
    // variant's choices (exact = 1, blinn_phong = 1, gerstner = 1, soft = 1).
    CHECK(s.variant->specialization.size() == 4);
    for (const auto& [id, value] : s.variant->specialization)
        CHECK(value == 1.0);
    // Frozen: the fragment SPIR-V is the variant's own, with the selectors folded in.
    REQUIRE(s.variant->frozen.count("glsl"));
    const auto frozen = spec.spirv(*s.variant, "glsl", ShaderStage::Fragment, &error);
    REQUIRE(frozen);
    const std::string on_disk = test::read_file(spec.directory() / s.variant->frozen.at("glsl"));
    CHECK(on_disk.size() == frozen->size() * 4);
    CHECK(spec.reflection(*s.variant, "hlsl", ShaderStage::Fragment, &error));

    const ShaderBuild branching = test::open_mode_build(BuildMode::Branching);
    CHECK(branching.mode() == "branching");
    s = branching.select("open_ocean", wanted);
    REQUIRE(s.ok());
    CHECK(s.variant->selector_uniforms.size() == 4);
    // The writer presets the selectors (they choose the variant) and refuses to set them.
    UniformWriter w(*s.variant);
    REQUIRE(w.value("axis_fresnel"));
    CHECK(*w.value("axis_fresnel") == std::vector<float>{1.0f});
    const Write r = w.set("axis_fresnel", 0.0f);
    CHECK_FALSE(r.ok);
    CHECK_THAT(r.error, Catch::Contains("selects the variant"));
    const auto refl = branching.reflection(*s.variant, "glsl", ShaderStage::Fragment, &error);
    REQUIRE(refl);
    const auto bytes = w.pack(*refl, &error);
    INFO(error);
    REQUIRE(bytes);
    size_t checked = 0;
    for (const auto& m : refl->bindings[0].members)
        if (s.variant->selector_uniforms.count(m.name)) {
            float f = 0;
            std::memcpy(&f, bytes->data() + m.offset, 4);
            CHECK(f == 1.0f);
            ++checked;
        }
    CHECK(checked == 4);
}
