// watergen_shaders.h, the build's C++ header. generated/ holds the example build's (a test keeps
// generated/ equal to what the generator writes), so including it here compiles the header with
// every static_assert of its offsets and sizes; at run time it must list the manifest's
// variants in order and hold, in each interface's default block, every member's default at the
// offset the variant's description gives, and zero elsewhere.
#include <catch2/catch.hpp>

#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "build_test_support.h"
#include "watergen/ir/emit/uniform_layout.h"
#include "watergen/pipeline/record/shaders_header.h"
#include "watergen/pipeline/record/staged_tree.h"
#include "watergen/runtime/host_values.h"
#include "watergen_shaders.h"

using namespace watergen;

namespace {

Json read_json(const std::filesystem::path& path) {
    std::ifstream in(path);
    REQUIRE(in);
    return Json::parse(in);
}

// Interface i's members computed on the host (HostMember), as "name rule offset components
// elements input,input,...".
std::vector<std::string> host_members(uint32_t i) {
    return watergen_default::with_interface(i, [](auto block) {
        std::vector<std::string> out;
        for (const watergen_shaders::HostMember& m : decltype(block)::kHostMembers) {
            std::string inputs;
            for (const char* in : m.inputs)
                if (in) inputs += (inputs.empty() ? "" : ",") + std::string(in);
            out.push_back(std::string(m.name) + " " + m.rule + " " + std::to_string(m.offset) +
                          " " + std::to_string(m.components) + " " + std::to_string(m.elements) +
                          " " + inputs);
        }
        return out;
    });
}

// Interface i's default block as floats.
std::vector<float> default_block(uint32_t i) {
    return watergen_default::with_interface(i, [](auto block) {
        std::vector<float> floats(sizeof block / sizeof(float));
        std::memcpy(floats.data(), &block, sizeof block);
        return floats;
    });
}

// A file of generated/, as the header writer reads its output.
std::optional<std::string> read_generated(const std::string& path) {
    std::ifstream in(std::filesystem::path(test::source_dir()) / "generated" / path,
                     std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace

TEST_CASE("the_build_header_lists_every_variant_with_its_default_block", "[golden]") {
    const std::filesystem::path generated = std::filesystem::path(test::source_dir()) / "generated";
    const Json manifest = read_json(generated / "manifest.json");
    const Json& variants = manifest.at("variants");
    REQUIRE(watergen_default::kVariants.size() == variants.size());
    CHECK(std::string(watergen_default::kMaterial) == "default");
    CHECK(std::string(watergen_default::kBindingMap) == manifest["bindings"]["map"]);
    CHECK(watergen_default::bindings::WaterParams.binding ==
          manifest["bindings"]["resources"]["WaterParams"]["binding"]);
    CHECK(watergen_default::bindings::sky_cube.binding ==
          manifest["bindings"]["resources"]["sky_cube"]["binding"]);
    size_t members = 0, host_count = 0;
    for (size_t k = 0; k < variants.size(); ++k) {
        const Json& v = variants[k];
        const watergen_shaders::VariantInfo& info = watergen_default::kVariants[k];
        INFO(v["scene"].get<std::string>() << " " << v["key"].get<std::string>());
        CHECK(info.scene == v["scene"].get<std::string>());
        CHECK(info.key == v["key"].get<std::string>());
        CHECK(info.hash == v["hash"].get<std::string>());
        const Json d = read_json(generated / v["files"]["description"][0].get<std::string>());
        const Json& block = d["uniform_block"];
        const std::vector<float> floats = default_block(info.interface_index);
        REQUIRE(floats.size() * sizeof(float) == block["size"].get<size_t>());
        std::vector<bool> member_float(floats.size(), false);
        // A member with a host rule holds what the rule makes of the defaults, in the frame
        // around the default eye (host_values.h); the others hold their defaults.
        std::map<std::string, std::vector<double>> defaults;
        for (const Json& m : block["members"])
            defaults[m["name"].get<std::string>()] = m["default"].get<std::vector<double>>();
        Frame frame;
        if (auto eye = defaults.find("eye_position"); eye != defaults.end())
            frame.centre = frame_centre_of(eye->second[0], eye->second[2]);
        const GivenValues given = [&](const std::string& name) -> const std::vector<double>* {
            auto it = defaults.find(name);
            return it == defaults.end() ? nullptr : &it->second;
        };
        std::vector<std::string> hosts;
        for (const Json& m : block["members"]) {
            std::vector<double> values = m["default"];
            if (m.contains("host")) {
                std::string inputs;
                for (const Json& in : m["host"]["inputs"])
                    inputs += (inputs.empty() ? "" : ",") + in.get<std::string>();
                const std::string type = m["type"];
                hosts.push_back(m["name"].get<std::string>() + " " +
                                m["host"]["rule"].get<std::string>() + " " +
                                std::to_string(m["offset"].get<uint32_t>()) + " " +
                                (type == "float" ? "1" : type.substr(3, 1)) + " " +
                                std::to_string(m.value("array_size", 0u)) + " " + inputs);
                const auto rule = host_rule_from_name(m["host"]["rule"].get<std::string>());
                REQUIRE(rule);
                const HostValue h{*rule, m["host"]["inputs"].get<std::vector<std::string>>()};
                std::string error;
                const auto v = host_value(h, values, given, frame, &error);
                INFO(m["name"].get<std::string>() << ": " << error);
                REQUIRE(v);
                values = *v;
            }
            const size_t n = m["type"] == "float" ? 1 : m["type"].get<std::string>()[3] - '0';
            for (size_t i = 0; i < values.size(); ++i) {
                const size_t at = (m["offset"].get<size_t>() + (i / n) * kArrayStride) / 4 + i % n;
                REQUIRE(at < floats.size());
                CHECK(floats[at] == static_cast<float>(values[i]));
                member_float[at] = true;
            }
            ++members;
        }
        for (size_t at = 0; at < floats.size(); ++at)
            if (!member_float[at]) CHECK(floats[at] == 0.0f);
        // The header says which members the host computes, and from what, as the manifest does.
        CHECK(host_members(info.interface_index) == hosts);
        host_count += hosts.size();
    }
    CHECK(host_count > 50); // the eye is framed in every variant (56)
    CHECK(members > 1000);  // every variant's members were compared (56 variants)
}

TEST_CASE("the_build_header_is_what_the_generator_writes_for_that_output", "[golden]") {
    std::string error;
    const auto header = shaders_header(read_generated, &error);
    INFO(error);
    REQUIRE(header);
    CHECK(*header == read_generated(kShadersHeader));
    CHECK(header->find("kConstants") != std::string::npos);
}

TEST_CASE("a_build_header_needs_its_manifest_and_descriptions", "[unit]") {
    std::string error;
    CHECK_FALSE(shaders_header([](const std::string&) { return std::nullopt; }, &error));
    CHECK(error == "manifest.json: missing");
    const std::string manifest = R"({"material": {"name": "m"}, "variants": [
        {"scene": "s", "key": "k", "hash": "h", "files": {"description": ["s/k/variant.json"]}}]})";
    CHECK_FALSE(shaders_header(
        [&](const std::string& path) -> std::optional<std::string> {
            if (path == "manifest.json") return manifest;
            return std::nullopt;
        },
        &error));
    CHECK(error == "s/k/variant.json: missing");
}

// A build of a few thousand variants writes a manifest larger than the staging tree reads back
// (64 MB; 18 KB a variant with every target): the header reads it as it goes. Before, such a
// build and the merge of its shards failed with "watergen_shaders.h: manifest.json: missing".
TEST_CASE("the_header_of_a_tree_reads_a_manifest_past_the_trees_read_back_cap", "[unit]") {
    const test::TempDir tmp("header-large-manifest");
    std::string error;
    const auto tree = StagedTree::open(tmp.path / "out", &error);
    REQUIRE(tree);
    nlohmann::ordered_json m = nlohmann::ordered_json::parse(*read_generated("manifest.json"));
    const nlohmann::ordered_json first = m["variants"][0];
    m["variants"] = nlohmann::ordered_json::array({first});
    const std::string description = first["files"]["description"][0];
    REQUIRE_FALSE(tree->write(description, *read_generated(description)));
    m["padding"] = std::string(size_t(65) << 20, ' ');
    REQUIRE_FALSE(tree->write("manifest.json", m.dump()));
    REQUIRE_FALSE(tree->read("manifest.json")); // past the cap
    const auto written = write_shaders_header(*tree);
    INFO(written.value_or(""));
    CHECK_FALSE(written);
    const auto header = tree->read(kShadersHeader);
    REQUIRE(header);
    CHECK(header->find(first["key"].get<std::string>()) != std::string::npos);
    CHECK(header->find("std::array<VariantInfo, 1> kVariants") != std::string::npos);
}

// A build whose map pushes the block: the header states the range and asserts that every
// interface's struct fits in it (the generator has refused any variant whose block does not).
TEST_CASE("a_pushed_build_header_states_its_range_and_asserts_each_block_fits", "[golden]") {
    std::string error;
    const auto header = shaders_header(
        [&](const std::string& path) -> std::optional<std::string> {
            std::optional<std::string> text = read_generated(path);
            if (!text || path != "manifest.json") return text;
            nlohmann::ordered_json m = nlohmann::ordered_json::parse(*text);
            m["bindings"]["resources"]["WaterParams"] = {
                {"kind", "push_constant"}, {"msl", 0}, {"gl", 0}};
            m["bindings"]["push_constant_bytes"] = 512;
            return m.dump(2);
        },
        &error);
    INFO(error);
    REQUIRE(header);
    CHECK(header->find("inline constexpr uint32_t kPushConstantBytes = 512;") != std::string::npos);
    CHECK(header->find("inline constexpr Slot WaterParams{0, 0, 0, 0, 0, 0}; // push_constant") !=
          std::string::npos);
    size_t asserts = 0;
    for (size_t at = header->find("<= kPushConstantBytes);"); at != std::string::npos;
         at = header->find("<= kPushConstantBytes);", at + 1))
        ++asserts;
    CHECK(asserts == 34); // one per interface of the example build
}
