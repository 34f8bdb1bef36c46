// The runtime library on a build's files gone wrong (a hostile-input round found each through
// the example consumer): a vertex module in the fragment slot, a truncated, byte-flipped or
// foreign .opt.spv, a reflection of 100,000 bindings, manifests near and past the size limit, a
// manifest binding map of the wrong shape.
// Each is an error naming the file and what was expected; none reaches the driver or builds a
// DOM of gigabytes. The big files are made here, in a temporary copy of a real build.
#include <catch2/catch.hpp>

#include <cstring>
#include <fstream>
#include <functional>
#include <tuple>

#include <nlohmann/json.hpp>

#include "engine_builds.h"
#include "watergen/runtime/binding_layout.h"
#include "watergen/runtime/spirv_check.h"

using namespace watergen;
namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void put(const fs::path& p, const std::string& bytes) {
    std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
}

// A copy of the example build (scenes applied) to break, and its first variant.
struct Copy {
    test::TempDir dir{"engine-hostile"};
    fs::path out = dir.path / "out";
    Copy() { fs::copy(test::example_build(true), out, fs::copy_options::recursive); }
    ShaderBuild open() const {
        std::string error;
        auto b = ShaderBuild::open(out, &error);
        INFO(error);
        REQUIRE(b);
        return *b;
    }
};

// The path of `v`'s file of `kind` ending in `suffix`, relative to the build.
std::string file_of(const BuildVariant& v, const std::string& kind, const std::string& suffix) {
    for (const std::string& p : v.files.at(kind))
        if (p.size() > suffix.size() &&
            p.compare(p.size() - suffix.size(), suffix.size(), suffix) == 0)
            return p;
    FAIL("no " << kind << " file " << suffix);
    return "";
}

std::string spirv_error(const ShaderBuild& b, const BuildVariant& v, ShaderStage stage) {
    std::string error;
    CHECK_FALSE(b.spirv(v, "glsl", stage, &error));
    return error;
}

} // namespace

TEST_CASE("a vertex module in the fragment slot is refused, naming the file and the stage") {
    const Copy c;
    const ShaderBuild b = c.open();
    const BuildVariant& v = b.variants().front();
    const std::string frag = file_of(v, "spirv", "/glsl/water.frag.opt.spv");
    put(c.out / frag, slurp(c.out / file_of(v, "spirv", "/glsl/water.vert.opt.spv")));
    CHECK(spirv_error(b, v, ShaderStage::Fragment) ==
          (c.out / frag).string() +
              ": has no OpEntryPoint Fragment (its entry points: Vertex main); expected the "
              "fragment stage's SPIR-V module");
    // The same words handed to the pipeline directly: check_spirv() (VariantPipeline::create
    // runs it before any Vulkan call) says so too, with the reflection's entry point.
    std::string why;
    const auto vert = b.spirv(v, "glsl", ShaderStage::Vertex, &why);
    REQUIRE(vert);
    CHECK(check_spirv(*vert, ShaderStage::Vertex, "main", &why));
    CHECK_FALSE(check_spirv(*vert, ShaderStage::Fragment, "main", &why));
    CHECK(why == "has no OpEntryPoint Fragment main (its entry points: Vertex main); expected "
                 "the fragment stage's SPIR-V module");
    CHECK_FALSE(check_spirv(*vert, ShaderStage::Compute, "", &why));
    CHECK_THAT(why, Catch::StartsWith("has no OpEntryPoint GLCompute (its entry points:"));
}

TEST_CASE("a truncated, byte-flipped or foreign .opt.spv is refused before any driver sees it") {
    const Copy c;
    const ShaderBuild b = c.open();
    const BuildVariant& v = b.variants().front();
    const std::string frag = file_of(v, "spirv", "/glsl/water.frag.opt.spv");
    const std::string path = (c.out / frag).string();
    const std::string good = slurp(c.out / frag);
    REQUIRE(good.size() > 1000);
    std::string ok;
    REQUIRE(b.spirv(v, "glsl", ShaderStage::Fragment, &ok));

    SECTION("truncated to 100 bytes: an instruction runs past the end") {
        put(c.out / frag, good.substr(0, 100));
        const std::string e = spirv_error(b, v, ShaderStage::Fragment);
        CHECK_THAT(e, Catch::StartsWith(path + ": instruction at word "));
        CHECK_THAT(e,
                   Catch::EndsWith("left; expected a whole SPIR-V module (truncated or corrupt?)"));
    }
    SECTION("truncated to 101 bytes: not whole words") {
        put(c.out / frag, good.substr(0, 101));
        CHECK(spirv_error(b, v, ShaderStage::Fragment) ==
              path + ": 101 bytes; expected a whole number of 32-bit words (SPIR-V)");
    }
    SECTION("truncated to 12 bytes: shorter than the header") {
        put(c.out / frag, good.substr(0, 12));
        CHECK(spirv_error(b, v, ShaderStage::Fragment) ==
              path + ": 12 bytes, shorter than the SPIR-V header; expected the fragment stage's "
                     "SPIR-V module");
    }
    SECTION("every byte after the header flipped: the first instruction's word count is wrong") {
        std::string bad = good;
        for (size_t i = 20; i < bad.size(); ++i)
            bad[i] = static_cast<char>(~bad[i]);
        put(c.out / frag, bad);
        CHECK_THAT(spirv_error(b, v, ShaderStage::Fragment),
                   Catch::StartsWith(path + ": instruction at word 5 (opcode "));
    }
    SECTION("one operand byte flipped in the middle: spirv-val rejects it") {
        // The structure holds (only an operand changes), so only the validator can tell.
        std::vector<uint32_t> words(good.size() / 4);
        std::memcpy(words.data(), good.data(), good.size());
        size_t at = 5, flipped = 0;
        while (at < words.size()) { // the first OpTypePointer (32) past the middle: its type id
            const uint32_t count = words[at] >> 16, opcode = words[at] & 0xFFFF;
            if (opcode == 32 && at > words.size() / 8) {
                flipped = at + 3;
                break;
            }
            at += count;
        }
        REQUIRE(flipped != 0);
        words[flipped] ^= 0x00FF0000;
        std::string bad(good.size(), '\0');
        std::memcpy(bad.data(), words.data(), bad.size());
        put(c.out / frag, bad);
        std::string why;
        REQUIRE(check_spirv(words, ShaderStage::Fragment, "main", &why));
        CHECK_THAT(spirv_error(b, v, ShaderStage::Fragment),
                   Catch::StartsWith(path + ": spirv-val: ") &&
                       Catch::EndsWith("; expected a valid SPIR-V module"));
    }
    SECTION("a wrong magic number, and SPIR-V of the other byte order") {
        std::string bad = good;
        const uint32_t magic = 0xDEADBEEF;
        std::memcpy(bad.data(), &magic, 4);
        put(c.out / frag, bad);
        CHECK(spirv_error(b, v, ShaderStage::Fragment) ==
              path + ": magic number 0xdeadbeef; expected 0x07230203 (SPIR-V)");
        bad = good; // every word's bytes reversed: a big-endian module on this machine
        for (size_t w = 0; w + 4 <= bad.size(); w += 4)
            std::swap(bad[w], bad[w + 3]), std::swap(bad[w + 1], bad[w + 2]);
        put(c.out / frag, bad);
        CHECK(spirv_error(b, v, ShaderStage::Fragment) ==
              path + ": SPIR-V in the other byte order (magic 0x03022307); expected words in "
                     "this machine's byte order");
    }
    SECTION("larger than any module the generator writes") {
        std::string big = good;
        big.resize(kMaxSpirvBytes + 4, '\0');
        put(c.out / frag, big);
        CHECK(spirv_error(b, v, ShaderStage::Fragment) ==
              path + ": " + std::to_string(kMaxSpirvBytes + 4) + " bytes; expected at most " +
                  std::to_string(kMaxSpirvBytes) + " (no watergen build writes a larger one)");
    }
}

TEST_CASE("a reflection of 100,000 bindings, or past any bound a real one has, is refused") {
    const Copy c;
    const ShaderBuild b = c.open();
    const BuildVariant& v = b.variants().front();
    const std::string refl = file_of(v, "reflection", "/glsl/water.frag.reflect.json");
    const std::string path = (c.out / refl).string();
    auto bindings = [](size_t n, const std::string& extra = "") {
        std::string s = R"({"stage": "fragment", "entry_point": "main", "inputs": [], )"
                        R"("outputs": [], "bindings": [)";
        for (size_t i = 0; i < n; ++i)
            s += std::string(i ? "," : "") + R"({"name":"t","set":0,"binding":)" +
                 std::to_string(i % 1000) + R"(,"kind":"sampler")" + extra + "}";
        return s + "]}";
    };
    std::string error;
    put(c.out / refl, bindings(100000));
    CHECK_FALSE(b.reflection(v, "glsl", ShaderStage::Fragment, &error));
    CHECK(error == path + ": " + std::to_string(bindings(100000).size()) +
                       " bytes; expected at most 1048576 (no watergen build writes a larger one)");
    // Within the size, past the count.
    put(c.out / refl, bindings(65));
    CHECK_FALSE(b.reflection(v, "glsl", ShaderStage::Fragment, &error));
    CHECK(error == path + ": bindings: 65 items; expected at most 64 (a watergen shader has far "
                          "fewer)");
    CHECK(reflection_from_json(bindings(64), &error));
    // A set no device is guaranteed to bind, and a block of gigabytes.
    CHECK_FALSE(reflection_from_json(
        R"({"stage":"fragment","entry_point":"main","inputs":[],"outputs":[],"bindings":[)"
        R"({"name":"b","set":9,"binding":0,"kind":"uniform_buffer"}]})",
        &error));
    CHECK(error == "bindings[0].set: 9; expected at most 3");
    CHECK_FALSE(reflection_from_json(
        R"({"stage":"fragment","entry_point":"main","inputs":[],"outputs":[],"bindings":[)"
        R"({"name":"b","set":0,"binding":0,"kind":"uniform_buffer","block_size":4294967295}]})",
        &error));
    CHECK(error == "bindings[0].block_size: 4294967295; expected at most 65536");
    // Small values by the hundred thousand: refused before a DOM is built.
    std::string many = R"({"stage":"fragment","entry_point":"main","x":[)";
    for (int i = 0; i < 70000; ++i)
        many += i ? ",0" : "0";
    CHECK_FALSE(reflection_from_json(many + "]}", &error));
    CHECK(error ==
          "(root): more than 65536 JSON values; expected a watergen reflection (a few KB)");
}

TEST_CASE("a manifest past the size limit, or of small values by the million, is refused") {
    test::TempDir dir("engine-hostile-manifest");
    std::string error;
    SECTION("larger than the generator's limit: refused by its size, unread") {
        { std::ofstream(dir.path / "manifest.json") << "{"; }
        fs::resize_file(dir.path / "manifest.json", (size_t(256) << 20) + 1); // sparse
        CHECK_FALSE(ShaderBuild::open(dir.path, &error));
        CHECK(error == (dir.path / "manifest.json").string() + ": 268435457 bytes; expected at "
                                                               "most 268435456 (no watergen "
                                                               "build writes a larger one)");
    }
    SECTION("under the limit, more values than a build of that size can hold") {
        // 34 MB of "0,": 17M values (a real manifest of 256 MiB holds under 9M).
        std::string text = R"({"generator": "watergen 0.1.0", "x": [)";
        const size_t n = (size_t(16) << 20) + 10;
        text.reserve(text.size() + 2 * n + 4);
        for (size_t i = 0; i < n; ++i)
            text += i ? ",0" : "0";
        put(dir.path / "manifest.json", text + "]}");
        CHECK_FALSE(ShaderBuild::open(dir.path, &error));
        CHECK(error == (dir.path / "manifest.json").string() +
                           ": more than 16777216 JSON values; expected the manifest of a "
                           "watergen build");
    }
    SECTION("nested deeper than the generator nests") {
        put(dir.path / "manifest.json", std::string(1000000, '[') + std::string(1000000, ']'));
        CHECK_FALSE(ShaderBuild::open(dir.path, &error));
        CHECK(error == (dir.path / "manifest.json").string() +
                           ": JSON nested more than 16 levels deep; expected the manifest of a "
                           "watergen build");
    }
}

// The manifest's binding map gone wrong: each an error naming the key; a map whose slots
// clash or reach past set 3 opens, and BindingLayout::create refuses it (no device needed to
// get there: the check comes first).
TEST_CASE("a manifest's binding map of the wrong shape is refused naming the key") {
    const Copy copy;
    const std::string text = slurp(copy.out / "manifest.json");
    const std::string kind = "\"kind\": \"texture\"";
    REQUIRE(text.find(kind) != std::string::npos);
    for (const auto& [from, to, says] :
         {std::tuple{kind, std::string("\"kind\": \"storage\""),
                     std::string("kind: 'storage'; expected uniform_block, sampler, texture or "
                                 "push_constant")},
          std::tuple{kind, std::string("\"kind\": 7"), std::string("kind: expected a string")},
          std::tuple{std::string("\"map\": \"watergen\""), std::string("\"map\": []"),
                     std::string("bindings.map: expected a string")}}) {
        INFO(to);
        std::string broken = text;
        broken.replace(broken.find(from), from.size(), to);
        put(copy.out / "manifest.json", broken);
        std::string error;
        CHECK_FALSE(ShaderBuild::open(copy.out, &error));
        CHECK(error.find(says) != std::string::npos);
        CHECK(error.find("manifest.json: bindings") != std::string::npos);
    }
    put(copy.out / "manifest.json", text);
    BuildBindings past = copy.open().bindings();
    REQUIRE(past.slots.size() == 14);
    past.slots.back().set = 7;
    std::string error;
    CHECK_FALSE(BindingLayout::create(VK_NULL_HANDLE, past, &error));
    CHECK(error.find("in set 7; expected a set below 4") != std::string::npos);
    BuildBindings twice = copy.open().bindings();
    twice.slots.back().set = twice.slots.front().set;
    twice.slots.back().binding = twice.slots.front().binding;
    CHECK_FALSE(BindingLayout::create(VK_NULL_HANDLE, twice, &error));
    CHECK(error.find("are both at set 0 binding 0") != std::string::npos);
}

// A map whose parameter block is a push constant: the slot has no set, binding or HLSL register,
// and the map states the range's bytes; without them, at a size no range has, or with a second
// push constant, an error naming the key.
TEST_CASE("a manifest's push-constant slot and range are read or refused naming the key") {
    const Copy copy;
    const fs::path file = copy.out / "manifest.json";
    const nlohmann::json original = nlohmann::json::parse(slurp(file));
    auto open_with = [&](const std::function<void(nlohmann::json&)>& change, std::string* error) {
        nlohmann::json doc = original;
        nlohmann::json& map = doc["bindings"];
        map["resources"]["WaterParams"] = {{"kind", "push_constant"}, {"msl", 5}, {"gl", 2}};
        map["push_constant_bytes"] = 128;
        change(map);
        put(file, doc.dump(2));
        return ShaderBuild::open(copy.out, error);
    };
    std::string error;
    const auto b = open_with([](nlohmann::json&) {}, &error);
    INFO(error);
    REQUIRE(b);
    CHECK(b->bindings().push_constant_bytes == 128);
    CHECK(b->bindings().slots.size() == 14);
    const MapSlot* params = b->bindings().find("WaterParams");
    REQUIRE(params);
    CHECK(params->kind == DescriptorKind::PushConstant);
    CHECK(params->set == 0);
    CHECK(params->binding == 0);
    CHECK(params->msl == 5);
    CHECK(params->gl == 2);
    // A map without a push constant states no range, whatever else it says.
    put(file, original.dump(2));
    CHECK(copy.open().bindings().push_constant_bytes == 0);

    const std::string at = file.string() + ": bindings.";
    for (const auto& [change, says] :
         std::vector<std::pair<std::function<void(nlohmann::json&)>, std::string>>{
             {[](nlohmann::json& m) { m.erase("push_constant_bytes"); },
              "push_constant_bytes: missing; expected an unsigned integer"},
             {[](nlohmann::json& m) { m["push_constant_bytes"] = "128"; },
              "push_constant_bytes: expected an unsigned integer"},
             {[](nlohmann::json& m) { m["push_constant_bytes"] = 130; },
              "push_constant_bytes: 130; expected a multiple of 4 from 4 to 4096 (the "
              "push-constant range of 'WaterParams')"},
             {[](nlohmann::json& m) { m["push_constant_bytes"] = 0; },
              "push_constant_bytes: 0; expected a multiple of 4 from 4 to 4096 (the "
              "push-constant range of 'WaterParams')"},
             {[](nlohmann::json& m) { m["push_constant_bytes"] = 8192; },
              "push_constant_bytes: 8192; expected a multiple of 4 from 4 to 4096 (the "
              "push-constant range of 'WaterParams')"},
             {[](nlohmann::json& m) { m["resources"]["WaterParams"].erase("msl"); },
              "resources.WaterParams.msl: missing; expected an unsigned integer"},
             {[](nlohmann::json& m) {
                  m["resources"]["linear_clamp"] = {
                      {"kind", "push_constant"}, {"msl", 0}, {"gl", 0}};
              },
              "resources.linear_clamp.kind: a second push_constant slot ('WaterParams' is "
              "one); expected at most one"}}) {
        INFO(says);
        CHECK_FALSE(open_with(change, &error));
        CHECK(error == at + says);
    }
}
