#include <catch2/catch.hpp>

#include <regex>

#include "watergen/plan/scene_file.h"

using namespace watergen;

namespace {

// A valid scene; `replace` swaps one line (matched by its key) for another text.
std::string scene_text(const std::string& key = "", const std::string& line = "") {
    std::vector<std::pair<std::string, std::string>> lines = {
        {"name", "  \"name\": \"lake\","},
        {"shoreline", "  \"shoreline\": true,"},
        {"water_depth", "  \"water_depth\": {\"min\": 0, \"max\": 30},"},
        {"camera_height", "  \"camera_height\": {\"min\": 1, \"max\": 20},"},
        {"camera_pitch", "  \"camera_pitch\": {\"min\": -60, \"max\": 10},"},
        {"sun_elevation", "  \"sun_elevation\": {\"min\": 5, \"max\": 60},"},
        {"reflection_sources", "  \"reflection_sources\": [\"cubemap\"],"},
        {"waves", "  \"waves\": \"animated\","},
        {"precision", "  \"precision\": \"full\","},
        {"platforms", "  \"platforms\": [\"vulkan\", \"metal\"]"},
    };
    std::string s = "{\n";
    for (const auto& [k, text] : lines) {
        if (k == key) {
            if (!line.empty()) s += line + "\n";
        } else {
            s += text + "\n";
        }
    }
    // Keep the JSON valid when the last line was replaced or dropped.
    s = std::regex_replace(s, std::regex(",\n$"), "\n");
    return s + "}\n";
}

std::string error_of(const std::string& text) {
    Diagnostic parse_error;
    const auto src = JsonSource::parse(text, "s.json", &parse_error);
    if (!src) return format_diagnostic(parse_error);
    Diagnostics ds;
    if (parse_scene(*src, ds)) return "";
    REQUIRE(ds.size() == 1);
    return format_diagnostic(ds.front());
}

} // namespace

TEST_CASE("a_valid_scene_reads_every_fact", "[scene]") {
    Diagnostic e;
    const auto src = JsonSource::parse(scene_text(), "dir/s.json", &e);
    REQUIRE(src);
    Diagnostics ds;
    const auto s = parse_scene(*src, ds);
    REQUIRE(s);
    CHECK(s->name == "lake");
    CHECK(s->file == "s.json");
    CHECK(s->shoreline);
    CHECK(s->water_depth.max == 30);
    CHECK(s->camera_pitch.min == -60);
    CHECK(s->reflection_sources == std::vector<std::string>{"cubemap"});
    CHECK(s->waves_animated);
    CHECK(s->platforms == std::vector<std::string>{"vulkan", "metal"});
    CHECK(s->where.of("water_depth") == "dir/s.json:4:3 /water_depth");
}

TEST_CASE("scene_errors_name_file_line_path_and_what_was_expected", "[scene]") {
    CHECK(error_of(scene_text("shoreline", "  \"shoreline\": \"yes\",")) ==
          "s.json:3:3: error: /shoreline: expected true or false, got a string (\"yes\")");
    CHECK(error_of(scene_text("shoreline")) ==
          "s.json:1:1: error: /: missing key 'shoreline' (a scene states every fact; see "
          "docs/user-guide.md \"Scene files\")");
    CHECK(error_of(scene_text("waves", "  \"waves\": \"choppy\",")) ==
          "s.json:9:3: error: /waves: unknown value 'choppy'; expected one of static, animated");
    CHECK(error_of(scene_text("water_depth", "  \"water_depth\": {\"min\": 30, \"max\": 3},")) ==
          "s.json:4:3: error: /water_depth: min 30 is above max 3; expected min <= max");
    CHECK(error_of(
              scene_text("water_depth", "  \"water_depth\": {\"min\": 3.0000001, \"max\": 3},")) ==
          "s.json:4:3: error: /water_depth: min 3.0000001 is above max 3; expected min <= max");
    CHECK(error_of(scene_text("water_depth",
                              "  \"water_depth\": {\"min\": 0, \"max\": 30, \"mean\": 4},")) ==
          "s.json:4:40: error: /water_depth/mean: unknown key 'mean'; expected min or max");
    CHECK(error_of(
              scene_text("sun_elevation", "  \"sun_elevation\": {\"min\": 5, \"max\": 90.5},")) ==
          "s.json:7:31: error: /sun_elevation/max: 90.5 degrees is out of range; expected a value "
          "in [-90, 90] degrees");
    CHECK(
        error_of(scene_text("camera_pitch", "  \"camera_pitch\": {\"min\": -120, \"max\": 10},")) ==
        "s.json:6:20: error: /camera_pitch/min: -120 degrees is out of range; expected a value in "
        "[-90, 90] degrees");
    CHECK(error_of(scene_text("platforms", "  \"platforms\": [\"vulkan\", \"playstation\"]")) ==
          "s.json:11:27: error: /platforms/1: unknown value 'playstation'; expected one of vulkan, "
          "d3d, opengl, gles, metal");
    CHECK(error_of(scene_text("platforms", "  \"platforms\": []")) ==
          "s.json:11:3: error: /platforms: no platform: the scene needs nothing; expected at least "
          "one of vulkan, d3d, "
          "opengl, gles, metal");
    CHECK(error_of(scene_text("reflection_sources",
                              "  \"reflection_sources\": [\"none\", \"planar\"],")) ==
          "s.json:8:3: error: /reflection_sources: 'none' cannot be listed with a source; expected "
          "[\"none\"] or sources "
          "from planar, cubemap, horizon_map");
    CHECK(error_of(scene_text("name", "  \"name\": \"lake\", \"colour\": 1,")) ==
          "s.json:2:19: error: /colour: unknown key 'colour'; expected one of name, description, "
          "shoreline, bottom_in_view, water_depth, "
          "camera_height, camera_pitch, sun_elevation, reflection_sources, waves, precision, "
          "platforms, fixed, scene_input");
    CHECK(error_of(scene_text("precision",
                              "  \"precision\": \"full\", \"scene_input\": \"gbuffer\",")) ==
          "s.json:10:24: error: /scene_input: unknown value 'gbuffer'; expected one of "
          "position_texture, depth_buffer, any");
    CHECK(error_of(scene_text("name", "  \"name\": \"Lake One\","))
              .find("/name: scene name 'Lake One': expected lower-case") != std::string::npos);
    CHECK(error_of(scene_text("water_depth", "  \"water_depth\": [0, 30],")) ==
          "s.json:4:3: error: /water_depth: expected an object {\"min\": number, \"max\": number}, "
          "got an array");
}

TEST_CASE("reflection_source_none_means_no_source", "[scene]") {
    Diagnostic e;
    const auto src = JsonSource::parse(
        scene_text("reflection_sources", "  \"reflection_sources\": [\"none\"],"), "s.json", &e);
    REQUIRE(src);
    Diagnostics ds;
    const auto s = parse_scene(*src, ds);
    REQUIRE(s);
    CHECK(s->reflection_sources.empty());
}
