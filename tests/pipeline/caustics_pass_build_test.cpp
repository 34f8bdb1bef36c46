// The companion caustics pass of `watergen build`: written once per (method, wave model) for a
// material offering area_ratio with Gerstner waves, referenced from every such variant's
// manifest entry and from no other, validated SPIR-V, parameters shared with the water
// variant's block under the same names, types and values, byte-identical output for 1 and 2
// threads and in every build mode, and covered by the build record.
#include <catch2/catch.hpp>

#include <cstring>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "build_test_support.h"
#include "watergen/pipeline/build/build_output.h"
#include "watergen/pipeline/manifest/caustics_pass_build.h"
#include "watergen/pipeline/record/build_record.h"
#include "watergen/toolchain/spirv_tools_stage.h"

using namespace watergen;
using namespace watergen::test;
using nlohmann::json;

namespace {

constexpr const char* kPass = "passes/caustics-area_ratio-gerstner";

// Flat or Gerstner waves, caustics none or area_ratio, full or half precision: 6 variants (flat
// water has no caustics pass: a rule), 2 of them with the pass. The material sets a wave
// parameter and the window, which the pass must take too.
Material caustics_material() {
    Diagnostics ds;
    auto m = MaterialBuilder("caustics")
                 .offer("waves", {"flat", "gerstner"})
                 .offer("caustics", {"none", "area_ratio"})
                 .offer("precision", {"full", "half"})
                 .parameter("gerstner_amplitude", {0.3})
                 .parameter("caustics_window", {-8.0, -8.0, 16.0})
                 .build(ds);
    INFO((ds.empty() ? "" : ds[0].message));
    REQUIRE(m);
    return *m;
}

BuildRequest request(const std::filesystem::path& out, unsigned threads) {
    BuildRequest r;
    r.material = caustics_material();
    r.out = out;
    r.options.threads = threads;
    return r;
}

std::vector<uint32_t> words(const std::string& bytes) {
    std::vector<uint32_t> w(bytes.size() / 4);
    std::memcpy(w.data(), bytes.data(), w.size() * 4);
    return w;
}

// name -> (type, default) of a uniform block as variant.json / pass.json list it.
std::map<std::string, std::pair<std::string, json>> members(const json& block) {
    std::map<std::string, std::pair<std::string, json>> out;
    for (const json& m : block["members"])
        out[m["name"]] = {m["type"], m["default"]};
    return out;
}

} // namespace

TEST_CASE("a build writes the caustics pass once and every area_ratio variant references it",
          "[build][caustics]") {
    const TempDir tmp("caustics-pass");
    const BuildSummary one = build_material(request(tmp.path / "one", 1));
    REQUIRE(one.ok());
    CHECK(one.variants == 6);
    const BuildSummary two = build_material(request(tmp.path / "two", 2));
    REQUIRE(two.ok());
    const auto files = read_tree(tmp.path / "one");
    CHECK(files == read_tree(tmp.path / "two")); // byte-identical for 1 and 2 threads
    CHECK(files.size() == one.files);

    // Once: one pass directory, 7 files per stage and language path minus the HLSL path's
    // cross-compiled texts (3 x 2), plus pass.json.
    std::set<std::string> pass_dirs;
    size_t pass_files = 0;
    for (const auto& [path, bytes] : files)
        if (path.rfind("passes/", 0) == 0) {
            pass_dirs.insert(path.substr(0, path.find('/', 7)));
            ++pass_files;
        }
    CHECK(pass_dirs == std::set<std::string>{kPass});
    CHECK(pass_files == 23);

    // Every module validates (the toolchain validated them; here again from the bytes written).
    size_t modules = 0;
    for (const auto& [path, bytes] : files)
        if (path.rfind(kPass, 0) == 0 && path.size() > 4 &&
            path.compare(path.size() - 4, 4, ".spv") == 0) {
            INFO(path);
            CHECK(validate_spirv(words(bytes), path).empty());
            ++modules;
        }
    CHECK(modules == 8); // 2 languages x 2 stages x (plain, optimised)

    const json manifest = json::parse(files.at("manifest.json"));
    const json pass = json::parse(files.at(std::string(kPass) + "/pass.json"));
    const auto pass_members = members(pass["uniform_block"]);
    size_t with_pass = 0;
    for (const json& v : manifest["variants"]) {
        INFO(v["key"]);
        const bool area_ratio = v["nodes"]["caustics"] == "caustics.area_ratio";
        CHECK(v.contains("passes") == area_ratio);
        if (!area_ratio) continue;
        ++with_pass;
        const json& c = v["passes"]["caustics"];
        CHECK(c["method"] == "area_ratio");
        CHECK(c["wave_model"] == "gerstner");
        CHECK(c["directory"] == kPass);
        CHECK(c["files"]["spirv"].size() == 8);
        CHECK(c["files"]["description"] == json::array({std::string(kPass) + "/pass.json"}));
        CHECK(c["draw"]["primitive"] == "triangles");
        CHECK(c["draw"]["blend"] == "additive");
        CHECK(c["draw"]["format"] == "R32_SFLOAT");
        CHECK(c["draw"]["texels"] == 64);
        CHECK(c["values"] == json::object()); // unpruned: nothing folded
        // One uniform set drives both passes: every parameter the two blocks share has the
        // same type and value (the material's, where it set one).
        const json variant =
            json::parse(files.at(v["directory"].get<std::string>() + "/variant.json"));
        std::set<std::string> shared;
        for (const auto& [name, water] : members(variant["uniform_block"]))
            if (const auto p = pass_members.find(name); p != pass_members.end()) {
                INFO(name);
                CHECK(p->second == water);
                shared.insert(name);
            }
        for (const char* name : {"time", "sun_direction", "caustics_window", "gerstner_amplitude",
                                 "gerstner_wave_directions", "ior_water"})
            CHECK(shared.count(name) == 1);
        // The wave count is a specialization constant (a loop bound) in both, same default.
        REQUIRE(pass.contains("specialization_constants"));
        CHECK(pass["specialization_constants"][0]["name"] == "gerstner_wave_count");
        CHECK(pass["specialization_constants"][0]["default"] ==
              variant["specialization_constants"][0]["default"]);
    }
    CHECK(with_pass == 2); // full and half precision: one pass for both
    CHECK(pass_members.at("gerstner_amplitude").second == json::array({0.3}));
    CHECK(pass_members.at("caustics_window").second == json::array({-8.0, -8.0, 16.0}));
}

TEST_CASE("the build record covers the pass files", "[build][caustics]") {
    const TempDir tmp("caustics-record");
    BuildRequest r = request(tmp.path / "out", 2);
    r.options.cache = BuildCache(tmp.path / "cache");
    r.inputs_hash = "caustics-record-test";
    REQUIRE(build_material(r).ok());
    REQUIRE(build_up_to_date(r)); // nothing changed: a no-op
    const auto record = read_record(record_file(r.options.cache, r.out));
    REQUIRE(record);
    size_t recorded = 0;
    for (const RecordedFile& f : record->files)
        recorded += f.path.rfind(kPass, 0) == 0;
    CHECK(recorded == 23);
    // A pass file changed: the build must run again.
    std::ofstream(r.out / kPass / "glsl/caustics.vert.glsl", std::ios::app) << "\n";
    CHECK_FALSE(build_up_to_date(r));
    const BuildSummary again = build_material(r);
    REQUIRE(again.ok());
    CHECK_FALSE(again.up_to_date);
    CHECK(build_up_to_date(r));
}

TEST_CASE("a warm build copies the pass from the cache, and a damaged entry is rebuilt",
          "[build][caustics][cache]") {
    const TempDir tmp("caustics-cache");
    auto build = [&](const char* out) {
        BuildRequest r = request(tmp.path / out, 2);
        r.options.cache = BuildCache(tmp.path / "cache");
        const BuildSummary s = build_material(r);
        REQUIRE(s.ok());
        CHECK(s.passes == 1);
        return std::make_pair(s, read_tree(tmp.path / out));
    };
    const auto [cold, cold_files] = build("cold");
    CHECK(cold.passes_cached == 0);
    const auto [warm, warm_files] = build("warm");
    CHECK(warm.passes_cached == 1);
    CHECK(warm.cache_rejected == 0);
    CHECK(warm_files == cold_files); // the same bytes as compiled ones

    // The entry's key is the pass's own: flip one byte of a file inside it.
    const BuildCache cache(tmp.path / "cache");
    const CausticsPassBuild probe = build_caustics_pass_files(
        caustics_material(), {CausticsMethod::AreaRatio, "gerstner"}, cache);
    CHECK(probe.cached);
    flip_a_byte(cache.entry(probe.content_hash));
    const auto [damaged, damaged_files] = build("damaged");
    CHECK(damaged.passes_cached == 0);
    CHECK(damaged.cache_rejected == 1);
    CHECK(damaged_files == cold_files);
    const auto [again, again_files] = build("again"); // the rebuilt entry was stored
    CHECK(again.passes_cached == 1);
    CHECK(again.cache_rejected == 0);
}

TEST_CASE("the specialized and branching modes reference the pass from each served variant",
          "[build][caustics]") {
    for (BuildMode mode : {BuildMode::Specialized, BuildMode::Branching}) {
        INFO(to_string(mode));
        const TempDir tmp(std::string("caustics-") + to_string(mode));
        BuildRequest r = request(tmp.path / "out", 2);
        r.mode = mode;
        REQUIRE(build_material(r).ok());
        const auto files = read_tree(r.out);
        const json manifest = json::parse(files.at("manifest.json"));
        CHECK(files.count(std::string(kPass) + "/glsl/caustics.vert.opt.spv") == 1);
        size_t with_pass = 0;
        for (const json& v : manifest["variants"]) {
            const bool area_ratio = v["nodes"]["caustics"] == "caustics.area_ratio";
            CHECK(v.contains("passes") == area_ratio);
            with_pass += area_ratio && v["passes"]["caustics"]["directory"] == kPass;
        }
        CHECK(with_pass == 2);
    }
}

TEST_CASE("a scene named passes is refused: it would share the passes' directory",
          "[build][caustics]") {
    SceneFacts scene = example_scenes().front();
    scene.name = "passes";
    Diagnostics ds;
    CHECK_FALSE(plan_build(caustics_material(), {scene}, ds));
    REQUIRE(ds.size() == 1);
    CHECK_THAT(ds[0].message, Catch::Contains("scene name 'passes' is reserved"));
}

TEST_CASE("render and compare draw the pass a build of the default material ships",
          "[build][caustics]") {
    // The passes are one builder's: for variants named by their choices the pass of a material
    // of the preset alone (no preset here), for the built-in material its own. Its preset sets
    // no parameter the pass reads otherwise than the nodes' defaults do (tropical_ocean's sun is
    // the default sun), so every file is the same bytes: sources, SPIR-V, the cross-compiled
    // texts, the reflection and pass.json.
    for (CausticsMethod method : {CausticsMethod::AreaRatio, CausticsMethod::PhotonSplat}) {
        INFO(to_string(method));
        const CausticsPassBuild shipped =
            build_caustics_pass_files(default_material(), {method, "gerstner"});
        const CausticsPassBuild drawn =
            build_caustics_pass_files(preset_material(nullptr), {method, "gerstner"});
        REQUIRE(shipped.ok());
        REQUIRE(drawn.ok());
        // Two languages' two stages: source, SPIR-V plain and optimised, reflection, and for the
        // GLSL path SPIRV-Cross's GLSL 330, ESSL 300 and MSL; pass.json.
        CHECK(shipped.files.size() == 23);
        CHECK(drawn.files == shipped.files);
        // The drawn pass carries the SPIR-V it is drawn with (built, not copied from a cache).
        CHECK_FALSE(drawn.cached);
        CHECK(drawn.languages[0].vertex.toolchain.spirv_optimized.size() > 0);
    }
}
