// watergen build --mode: the specialized and branching modes build one shader per precision and
// list every variant with the selector values that draw it; freezing writes per-variant SPIR-V.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "build_test_support.h"
#include "manifest_schema_walk.h"
#include "watergen/pipeline/build/build_output.h"
#include "watergen/plan/material.h"

using namespace watergen;
using namespace watergen::test;
namespace fs = std::filesystem;

TEST_CASE("the_specialized_manifest_lists_each_variant_with_its_constant_values", "[build]") {
    const TempDir tmp("specialized");
    BuildRequest r{default_material(), {}, tmp.path / "out", {}};
    r.mode = BuildMode::Specialized;
    r.freeze = true;
    const BuildSummary s = build_material(r);
    REQUIRE(s.ok());
    CHECK(s.variants == 144);
    CHECK(s.shaders == 2); // full and half precision
    const auto tree = read_tree(r.out);
    const auto m = nlohmann::json::parse(tree.at("manifest.json"));
    // Its keys are the schema's (runtime/manifest_schema.h), as generated/manifest.json's are.
    for (const std::string& fault : unschemed_paths(m))
        FAIL_CHECK(fault);
    CHECK(m["mode"] == "specialized");
    REQUIRE(m["shaders"].size() == 2);
    REQUIRE(m["variants"].size() == 144);
    // The full-precision shader switches seven axes, each on its own constant.
    const auto& full = m["shaders"][1];
    CHECK(full["variants"] == 96);
    REQUIRE(full["selectors"].size() == 7);
    std::map<std::string, int> ids;
    for (const auto& sel : full["selectors"])
        ids[sel["parameter"]] = sel["constant_id"];
    for (const auto& v : m["variants"]) {
        INFO(v["key"]);
        CHECK(tree.count(v["shader"].get<std::string>() + "/glsl/water.frag.opt.spv") == 1);
        CHECK(tree.count(v["frozen"]["glsl"].get<std::string>()) == 1);
        CHECK(tree.count(v["frozen"]["hlsl"].get<std::string>()) == 1);
        if (v["shader"] != full["directory"]) continue;
        // Each constant value is the index of the variant's choice among the offered ones.
        REQUIRE(v["specialization_constants"].size() == 7);
        for (const auto& c : v["specialization_constants"]) {
            CHECK(c["id"] == ids[c["name"]]);
            const std::string axis = c["name"].get<std::string>().substr(5); // "axis_"
            const std::string choice = v["nodes"][axis].get<std::string>().substr(axis.size() + 1);
            const auto& offered = full["axes"][axis];
            CHECK(offered[c["value"].get<size_t>()] == choice);
        }
    }
    // The shader reflects its selectors as specialization constants with their ranges, and the
    // parameters declared as ones: the Gerstner wave count (a loop's trip count).
    const auto& constants = full["reflection"]["specialization_constants"];
    CHECK(constants.size() == 8);
    for (const auto& c : constants) {
        if (c["name"] != "gerstner_wave_count") continue;
        CHECK(c["default"][0] == 4.0);
        CHECK(c["max"] == 8.0);
        CHECK(ids.count("gerstner_wave_count") == 0); // a parameter, not a selector
    }
}

TEST_CASE("the_branching_manifest_places_the_selectors_in_the_uniform_block", "[build]") {
    const TempDir tmp("branching");
    BuildRequest r{default_material(), example_scenes(), tmp.path / "out", {}};
    r.mode = BuildMode::Branching;
    const BuildSummary s = build_material(r);
    REQUIRE(s.ok());
    CHECK(s.variants == 56); // the pruned scenes reach 16, 16 and 24 variants
    CHECK(s.shaders == 3);   // each scene targets one precision
    const auto m = nlohmann::json::parse(read_tree(r.out).at("manifest.json"));
    for (const std::string& fault : unschemed_paths(m))
        FAIL_CHECK(fault);
    REQUIRE(m["variants"].size() == 56);
    for (const auto& v : m["variants"]) {
        INFO(v["key"]);
        CHECK(v.contains("specialization_constants") == false);
        for (const auto& u : v["uniforms"]) {
            CHECK(u["offset"].get<int>() >= 0);
            CHECK(v["selectors"][u["name"].get<std::string>()] == u["value"]);
        }
    }
    for (const auto& sh : m["shaders"])
        for (const auto& sel : sh["selectors"])
            CHECK(sel.contains("offset")); // every switch survived the scene's fold
}

TEST_CASE("a_warm_frozen_build_copies_each_frozen_module_and_rebuilds_a_damaged_one",
          "[build][cache]") {
    const TempDir tmp("frozen-cache");
    Diagnostics ds;
    const auto material = MaterialBuilder("frozen")
                              .offer("fresnel", {"schlick", "exact"})
                              .offer("specular", {"none", "blinn_phong"})
                              .build(ds);
    REQUIRE(material);
    auto build = [&](const char* out) {
        BuildRequest r{*material, {}, tmp.path / out, {}};
        r.mode = BuildMode::Specialized;
        r.freeze = true;
        r.options.cache = BuildCache(tmp.path / "cache");
        const BuildSummary s = build_material(r);
        REQUIRE(s.ok());
        CHECK(s.frozen == 8); // 4 variants, GLSL and HLSL paths
        return std::make_pair(s, read_tree(r.out));
    };
    const auto [cold, cold_files] = build("cold");
    CHECK(cold.frozen_cached == 0);
    const auto [warm, warm_files] = build("warm");
    CHECK(warm.frozen_cached == 8);
    CHECK(warm_files == cold_files); // the bytes spirv-opt wrote

    // Flip one byte of one frozen module's entry: it fails verification and is frozen again.
    fs::path entry;
    for (const auto& f : fs::recursive_directory_iterator(tmp.path / "cache"))
        if (f.is_regular_file() && read_file(f.path()).find("\nfrozen.spv\n") != std::string::npos)
            entry = f.path();
    REQUIRE_FALSE(entry.empty());
    flip_a_byte(entry);
    const auto [damaged, damaged_files] = build("damaged");
    CHECK(damaged.cache_rejected == 1);
    CHECK(damaged.frozen_cached == 7);
    CHECK(damaged_files == cold_files);
}
