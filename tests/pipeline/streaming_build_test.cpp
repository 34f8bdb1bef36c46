// The streaming build: its manifest written one entry at a time reads exactly as one document's
// dump, a shard plans its own jobs only, and a shard of the full space builds in bounded memory.
#include <catch2/catch.hpp>

#include <sys/resource.h>

#include <cstdio>

#include <string>

#include "build_test_support.h"
#include "watergen/pipeline/build/build_output.h"
#include "watergen/pipeline/output/json_document.h"
#include "watergen/pipeline/shards/sharded_build.h"
#include "watergen/plan/scene_file.h"

using namespace watergen;
using namespace watergen::test;
namespace fs = std::filesystem;
using OJson = nlohmann::ordered_json;

namespace {

OJson sample_document() {
    OJson doc;
    doc["generator"] = "watergen 0.1.0";
    doc["material"] = {{"name", "two\nlines \"quoted\""}, {"axes", OJson::object()}};
    doc["empty"] = OJson::array();
    doc["shaders"] = OJson::array();
    doc["variants"] = {
        {{"key", "a"}, {"files", {{"glsl", {"a/x.glsl", "a/y.glsl"}}}}, {"n", 1.5}},
        {{"key", "b"}, {"nested", {{"deep", {OJson::array(), OJson::object(), nullptr}}}}},
        7};
    return doc;
}

} // namespace

TEST_CASE("a document written piece by piece reads as its whole dump", "[unit]") {
    const OJson doc = sample_document();
    OJson head = doc;
    head.erase("shaders");
    head.erase("variants");
    std::string text;
    const WriteText write = [&](std::string_view piece) { text += piece; };
    JsonDocumentWriter w(head, write);
    for (const char* array : {"shaders", "variants"}) {
        w.begin_array(array);
        for (const OJson& e : doc[array])
            w.element(e);
        w.end_array();
    }
    w.end();
    CHECK(text == doc.dump(2) + "\n"); // manifest.json's format, byte for byte

    // Read back: the head's members whole, the streamed arrays one element at a time.
    OJson members = OJson::object(), elements = OJson::array();
    std::vector<std::string> opened;
    const JsonDocumentReader reader{{"shaders", "variants"},
                                    [&](const std::string& name, OJson&& v) {
                                        members[name] = std::move(v);
                                        return true;
                                    },
                                    [&](const std::string& array, OJson&& e) {
                                        elements.push_back({array, std::move(e)});
                                        return true;
                                    },
                                    [&](const std::string& array) { opened.push_back(array); }};
    std::string why;
    REQUIRE(read_json_document(std::string_view(text), reader, &why) == JsonReadEnd::Done);
    CHECK(members == head);
    CHECK(opened == std::vector<std::string>{"shaders", "variants"});
    REQUIRE(elements.size() == 3);
    CHECK(elements[0] == OJson{"variants", doc["variants"][0]});
    CHECK(elements[2] == OJson{"variants", 7});

    CHECK(read_json_document(std::string_view("{\"a\": [1, 2"), reader, &why) ==
          JsonReadEnd::Malformed);
    CHECK_FALSE(why.empty());
    CHECK(read_json_document(std::string_view("[1]"), reader, &why) == JsonReadEnd::Malformed);
    const JsonDocumentReader first_only{{},
                                        [](const std::string&, OJson&&) { return false; },
                                        [](const std::string&, OJson&&) { return true; }};
    CHECK(read_json_document(std::string_view(text), first_only, &why) == JsonReadEnd::Stopped);
}

TEST_CASE("a shard plans only its own jobs and counts the whole space", "[unit]") {
    Diagnostics ds;
    const auto material = load_material(source_dir() + "/examples/materials/full.json", ds);
    REQUIRE(material);
    const Shard shard{3, 4000};
    size_t expected = 0;
    enumerate(material->space, [&](const Variant& v) { expected += in_shard(shard, v.key()); });
    const auto plan = plan_build(*material, {}, ds, BuildMode::Permutations, shard);
    REQUIRE(plan);
    CHECK(plan->jobs.size() == expected);
    CHECK(expected > 700); // 3,502,080 / 4000 = 876 on average
    std::string last;
    for (size_t i = 0; i < plan->jobs.size(); ++i) {
        const std::string key = job_key(plan->jobs.at(i));
        CHECK(in_shard(shard, key));
        CHECK(last < key); // sorted by key, each once
        last = key;
    }
    REQUIRE(plan->manifest_scenes.size() == 1);
    CHECK(plan->manifest_scenes[0].variants == 3502080); // the manifest counts the whole space
}

TEST_CASE("a shard of scene builds plans its own jobs, sorted by scene and key", "[unit]") {
    // A scene's reached variants and its jobs are kept a byte an axis (VariantList): the three
    // example scenes reach 1,376,640 of the full space, which as Variants took 506 MB for
    // mountain_lake's 875,520 alone.
    Diagnostics ds;
    const auto material = load_material(source_dir() + "/examples/materials/full.json", ds);
    REQUIRE(material);
    std::vector<SceneFacts> scenes;
    for (const char* name : {"open_ocean", "mountain_lake", "harbour_night"}) {
        auto scene = load_scene(source_dir() + "/examples/scenes/" + name + ".json", ds);
        REQUIRE(scene);
        scenes.push_back(std::move(*scene));
    }
    const Shard shard{3, 4000};
    const auto plan = plan_build(*material, scenes, ds, BuildMode::Permutations, shard);
    REQUIRE(plan);
    size_t reached = 0, expected = 0;
    for (const ScenePlan& p : plan->scenes) {
        reached += p.variants.size();
        for (const Variant& v : p.variants)
            expected += in_shard(shard, v.key());
    }
    CHECK(reached == 1376640);
    CHECK(plan->jobs.size() == expected);
    CHECK(expected > 250); // 1,376,640 / 4000 = 344 on average
    std::pair<std::string, std::string> last;
    size_t unsorted = 0, outside = 0, unfolded = 0;
    for (size_t i = 0; i < plan->jobs.size(); ++i) {
        const BuildJob job = plan->jobs.at(i);
        const std::pair<std::string, std::string> id{job.scene, job_key(job)};
        unsorted += !(last < id);
        outside += !in_shard(shard, id.second);
        unfolded += job.facts == nullptr;
        last = id;
    }
    CHECK(unsorted == 0);
    CHECK(outside == 0);
    CHECK(unfolded == 0); // each folded under its scene's facts
    CHECK(plan->jobs.at(0).scene == "harbour_night");
}

TEST_CASE("a modes build plans each shader with the variants it serves, sorted by key", "[unit]") {
    // A modes build's shaders list every variant of the space between them, kept a byte an axis
    // (VariantList) where Variants took 1.2 GB for 721,920; the manifest merges their lists in
    // key order, so each must be sorted by key, the keys that leave out an axis at its default
    // (geometry, scene_input) among them.
    Diagnostics ds;
    const auto material = load_material(source_dir() + "/examples/materials/full.json", ds);
    REQUIRE(material);
    const auto plan = plan_build(*material, {}, ds, BuildMode::Specialized, Shard{});
    REQUIRE(plan);
    REQUIRE(plan->jobs.size() == 12); // per precision (2), geometry (3) and scene input (2)
    size_t served = 0, unsorted = 0, uncovered = 0;
    Variant v = default_variant();
    for (const BuildJob& job : plan->jobs.held()) {
        REQUIRE(job.shader);
        REQUIRE(job.serves);
        std::string last;
        for (size_t k = 0; k < job.serves->size(); ++k) {
            job.serves->fill(k, v);
            std::string key = v.key();
            unsorted += !(last < key);
            uncovered += !job.shader->covers(v);
            last = std::move(key);
        }
        served += job.serves->size();
    }
    CHECK(served == 3502080);
    CHECK(unsorted == 0);
    CHECK(uncovered == 0);
}

TEST_CASE("a shard of the full space builds in bounded memory", "[build]") {
    // Before the streaming build (fd34161) a shard planned every job of the space and held its
    // whole output: 975 MB at 1/4000 (180 variants), 1.32 GB at 1/400. Streamed, 75 MB at
    // 1/4000 and flat as the shard grows (docs/measurements.md "Builds"); 300 MB leaves room for
    // the toolchain's own growth while catching either regression.
    const TempDir tmp("streaming");
    const WatergenRun run =
        run_watergen({"build", source_dir() + "/examples/materials/full.json", "--shard", "2/8000",
                      "--no-cache", "-q", "--out", (tmp.path / "out").string()},
                     240);
    REQUIRE(run.exit_code == 0);
    CHECK(run.max_rss_kb > 0);
    CHECK(run.max_rss_kb < 300 * 1024);
    CHECK(fs::exists(tmp.path / "out" / "manifest.json"));
    CHECK(fs::exists(tmp.path / "out" / "shard.json"));
    // Nothing of the staging tree is left beside the output.
    size_t entries = 0;
    for (const auto& e : fs::directory_iterator(tmp.path)) {
        (void)e;
        ++entries;
    }
    CHECK(entries == 1);
}

// A document padded with blanks costs no memory: nlohmann's lexer keeps every byte since its
// last string or number, and the reader hands it each run of blanks as one (a shard.json with
// 1 GiB of blanks took 2.1 GB to merge). Its pieces are bounded too: a member past the reader's
// depth or value limit is malformed, never held whole.
TEST_CASE("a_json_document_padded_with_blanks_is_read_in_bounded_memory", "[streaming]") {
    const size_t blanks = size_t(256) << 20;
    std::FILE* file = std::tmpfile();
    REQUIRE(file);
    std::fputs("{\"head\": 1, \"files\": [", file);
    const std::string chunk(size_t(1) << 20, ' ');
    for (size_t written = 0; written < blanks; written += chunk.size())
        std::fwrite(chunk.data(), 1, chunk.size(), file);
    std::fputs("[\"a\", 1]\n\n\t ]}", file);
    std::rewind(file);
    rusage before{};
    getrusage(RUSAGE_SELF, &before);
    size_t elements = 0;
    const JsonDocumentReader reader{{"files"},
                                    [](const std::string&, OJson&&) { return true; },
                                    [&](const std::string&, OJson&& e) {
                                        elements += e == OJson{"a", 1} ? 1 : 0;
                                        return true;
                                    }};
    std::string why;
    CHECK(read_json_document(file, reader, &why) == JsonReadEnd::Done);
    std::fclose(file);
    rusage after{};
    getrusage(RUSAGE_SELF, &after);
    CHECK(elements == 1);
    // 256 MiB of blanks; the peak grows by less than 32 MiB (it grew by their size before).
    CHECK(after.ru_maxrss - before.ru_maxrss < 32 * 1024);

    JsonDocumentReader small = reader;
    small.max_depth = 2;
    small.max_piece_values = 4;
    CHECK(read_json_document(std::string_view("{\"files\": [[1, 2, 3, 4, 5]]}"), small, &why) ==
          JsonReadEnd::Malformed);
    CHECK(why.find("more than 4 values") != std::string::npos);
    CHECK(read_json_document(std::string_view("{\"files\": [[[[1]]]]}"), small, &why) ==
          JsonReadEnd::Malformed);
    CHECK(why.find("nested deeper than 2 levels") != std::string::npos);
    // A syntax error names the byte of the document, blanks counted.
    CHECK(read_json_document(std::string_view("{\"a\":      ]}"), reader, &why) ==
          JsonReadEnd::Malformed);
    CHECK(why.rfind("byte ", 0) == 0);
}
