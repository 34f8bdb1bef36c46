#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "build_test_support.h"
#include "watergen/pipeline/build/build_output.h"

using namespace watergen;
using namespace watergen::test;
namespace fs = std::filesystem;

TEST_CASE("output_is_byte_identical_for_one_thread_and_all_threads", "[build]") {
    const TempDir tmp("threads");
    BuildRequest one{default_material(), example_scenes(), tmp.path / "one", {}};
    one.options.threads = 1;
    const BuildSummary a = build_material(one);
    REQUIRE(a.ok());
    CHECK(a.variants == 56);
    CHECK(a.same == 8); // open_ocean folds shore=soft into shore=hard: 400 m of water
    const auto fa = read_tree(one.out);
    CHECK(fa.size() == a.files);
    CHECK(fa == reference_build()); // all threads, from the JSON file: the same bytes
}

TEST_CASE("a_build_run_a_few_jobs_at_a_time_writes_the_bytes_of_one_run", "[build]") {
    // Batches of 3: variants of open_ocean point at shaders of earlier batches (same_as), and
    // (with a twin of a scene, folded alike) a scene takes the files another scene's earlier
    // batch built, read back from the staging tree.
    const TempDir tmp("batches");
    std::vector<SceneFacts> scenes = example_scenes();
    SceneFacts twin = scenes.front();
    twin.name += "_twin";
    scenes.push_back(twin);
    for (const bool with_twin : {false, true}) {
        BuildRequest whole{default_material(), scenes, tmp.path / "whole", {}};
        if (!with_twin) whole.scenes.pop_back();
        BuildRequest batched = whole;
        batched.out = tmp.path / "batched";
        batched.batch_jobs = 3;
        const BuildSummary a = build_material(whole), b = build_material(batched);
        REQUIRE(a.ok());
        REQUIRE(b.ok());
        CHECK(b.variants == a.variants);
        CHECK(b.same == a.same);
        CHECK(b.same > 0);
        CHECK(b.shared == a.shared);
        CHECK(b.built == a.built);
        CHECK(b.files == a.files);
        CHECK(read_tree(batched.out) == read_tree(whole.out));
        if (with_twin) {
            CHECK(b.shared > 0);
            CHECK(b.shared == b.variants - b.same - b.built); // the twin's, all shared
        } else {
            CHECK(read_tree(batched.out) == reference_build());
        }
    }
}

TEST_CASE("an_unchanged_variant_comes_from_the_cache_with_the_same_bytes", "[build]") {
    const TempDir tmp("cache");
    BuildRequest r{default_material(), example_scenes(), tmp.path / "out", {}};
    r.options.cache = BuildCache(tmp.path / "cache");
    const BuildSummary cold = build_material(r);
    REQUIRE(cold.ok());
    CHECK(cold.cached == 0);
    const auto first = read_tree(r.out);
    CHECK(first == reference_build());
    const BuildSummary warm = build_material(r);
    REQUIRE(warm.ok());
    CHECK(warm.built == 0);
    CHECK(warm.cached + warm.shared + warm.same == warm.variants);
    CHECK(read_tree(r.out) == first);

    // A changed parameter value changes only the variants that read it.
    BuildRequest changed = r;
    auto& s = changed.material.parameters["shore_hardness"];
    s.value = std::vector<double>{2.0};
    const BuildSummary third = build_material(changed);
    REQUIRE(third.ok());
    CHECK(third.built > 0);
    CHECK(third.cached > 0);
}

TEST_CASE("manifest_lists_every_variant_sorted_with_reflection_and_counts", "[build]") {
    const auto tree = reference_build();
    const auto m = nlohmann::json::parse(tree.at("manifest.json"));
    CHECK(m["space"]["full"] == count_variants(full_space()));
    CHECK(m["space"]["material"] == 144);
    REQUIRE(m["variants"].size() == 56);
    std::string previous;
    for (const auto& v : m["variants"]) {
        const std::string key = v["scene"].get<std::string>() + "|" + v["key"].get<std::string>();
        CHECK(previous < key);
        previous = key;
        CHECK(v["hash"].get<std::string>().size() == 16);
        CHECK(v["nodes"]["fresnel"].get<std::string>().rfind("fresnel.", 0) == 0);
        CHECK(v["reflection"]["uniform_block"]["binding"] == 0);
        CHECK(v["spirv_instructions"]["glsl"]["fragment"].get<int>() > 0);
        // Every listed file exists.
        for (const auto& [kind, files] : v["files"].items())
            for (const auto& f : files)
                CHECK(tree.count(f.get<std::string>()) == 1);
    }
    // The mountain lake targets phones: ESSL, no HLSL.
    for (const auto& v : m["variants"])
        if (v["scene"] == "mountain_lake") {
            CHECK(v["files"].contains("essl300"));
            CHECK_FALSE(v["files"].contains("hlsl"));
            CHECK(v["folded_parameters"].contains(
                "water_level")); // read by every variant; time is not (flat water)
        }
}

TEST_CASE("a_build_without_scenes_builds_the_whole_material_unfolded", "[build]") {
    const TempDir tmp("unpruned");
    Diagnostics ds;
    auto small = MaterialBuilder("small")
                     .offer("fresnel", {"schlick", "exact"})
                     .offer("shore", {"hard", "soft"})
                     .build(ds);
    REQUIRE(small);
    BuildRequest r{*small, {}, tmp.path / "out", {}};
    const BuildSummary s = build_material(r);
    REQUIRE(s.ok());
    CHECK(s.variants == 4);
    CHECK(s.same == 0); // nothing is folded without scenes
    const auto tree = read_tree(r.out);
    CHECK(fs::is_directory(r.out / kUnprunedScene));
    const auto m = nlohmann::json::parse(tree.at("manifest.json"));
    for (const auto& v : m["variants"]) {
        CHECK(v["scene"] == kUnprunedScene);
        CHECK(v["folded_parameters"].empty());
    }
}

TEST_CASE("a_failing_variant_leaves_the_previous_output_untouched", "[build]") {
    const TempDir tmp("failing");
    const fs::path out = tmp.path / "out";
    fs::create_directories(out);
    std::ofstream(out / "previous.txt") << "previous\n";
    const std::string manifest =
        "{\"generator\": \"watergen 0.1.0\"}\n"; // a build may replace only its own output
    std::ofstream(out / "manifest.json") << manifest;
    Material broken = default_material();
    broken.space.offered("fresnel").push_back("bogus"); // no node: the variant cannot compose
    BuildRequest r{broken, {example_scenes().front()}, out, {}};
    const BuildSummary s = build_material(r);
    CHECK_FALSE(s.ok());
    CHECK(s.failed > 0);
    CHECK(read_tree(out) == std::map<std::string, std::string>{{"manifest.json", manifest},
                                                               {"previous.txt", "previous\n"}});
    for (const auto& e : fs::directory_iterator(tmp.path))
        CHECK(e.path().filename() == "out"); // no staging left
}

TEST_CASE("bad_scene_input_leaves_the_previous_output_untouched", "[build]") {
    const TempDir tmp("bad-scene");
    const fs::path out = tmp.path / "out";
    fs::create_directories(out);
    std::ofstream(out / "previous.txt") << "previous\n";
    auto scenes = example_scenes();
    scenes[0].fixed["colour"] = {1.0};
    BuildRequest r{default_material(), scenes, out, {}};
    const BuildSummary s = build_material(r);
    CHECK(s.bad_input);
    REQUIRE(s.diagnostics.size() == 1);
    CHECK(s.diagnostics[0].message.find("unknown parameter 'colour'") != std::string::npos);
    CHECK(read_tree(out).size() == 1);
}

TEST_CASE("the_cpp_example_program_and_the_json_file_build_the_same_bytes", "[build]") {
    const TempDir tmp("example");
    std::string scene_args, scene_flags;
    for (const auto& path : example_scene_paths()) {
        scene_args += " " + path;
        scene_flags += " --scene " + path;
    }
    const std::string cpp = std::string(WATERGEN_EXAMPLE) + " " + (tmp.path / "cpp").string() +
                            scene_args + " > /dev/null";
    const std::string json = std::string(WATERGEN_CLI) + " build -q --no-cache " + source_dir() +
                             "/examples/materials/default.json" + scene_flags + " --out " +
                             (tmp.path / "json").string() + " > /dev/null";
    REQUIRE(std::system(cpp.c_str()) == 0);
    REQUIRE(std::system(json.c_str()) == 0);
    const auto a = read_tree(tmp.path / "cpp"), b = read_tree(tmp.path / "json");
    CHECK(a.size() > 100);
    CHECK(a == b);
}
