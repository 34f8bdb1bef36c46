// The house as docs/layout.md draws it: every source folder of the generator, the evaluation
// layer and the runtime belongs to one layer of the table below, a layer includes only the
// layers it may use, every generator layer has its public header folder, and the layout table
// names every folder.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

fs::path source_dir() {
    const char* dir = std::getenv("WATERGEN_SOURCE_DIR");
    REQUIRE(dir != nullptr);
    return dir;
}

std::string read_text(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// One layer: its folders (relative to the source root; a folder's subfolders are the layer's
// too), and the prefixes of the `watergen/...` headers it may include.
struct Layer {
    std::string name;
    std::vector<std::string> folders;
    std::set<std::string> may_include;
};

// Generic first. The runtime: the engine library (runtime/src) includes only itself; the
// headless device (runtime/headless) the runtime and itself; the test runner (runtime/runner)
// those and itself; nothing in runtime/ includes the generator. runtime/reflection.h is the
// shader interface types every layer shares. The evaluation rooms (generator/eval/<room>) may
// use the whole generator, the runtime's three layers and the rooms before them; the CLI uses
// everything.
const std::vector<Layer>& layers() {
    static const std::vector<Layer> all = [] {
        const std::vector<std::string> generator = {"ir",      "water",     "caustics",
                                                    "plan",    "toolchain", "pipeline",
                                                    "runtime", "headless",  "runner"};
        const std::vector<std::string> rooms = {"image", "scene",  "draw",    "measure",
                                                "probe", "report", "compare", "bench"};
        auto gen = [](const std::string& name, std::set<std::string> uses) {
            uses.insert(name);
            return Layer{
                name, {"generator/" + name, "generator/include/watergen/" + name}, std::move(uses)};
        };
        std::vector<Layer> v = {
            Layer{"runtime", {"runtime/src", "runtime/include/watergen/runtime"}, {"runtime"}},
            Layer{"headless",
                  {"runtime/headless", "runtime/include/watergen/headless"},
                  {"runtime", "headless"}},
            Layer{"runner",
                  {"runtime/runner", "runtime/include/watergen/runner"},
                  {"runtime", "headless", "runner"}},
            gen("ir", {"runtime/reflection"}),
            gen("water", {"ir", "runtime/reflection"}),
            gen("caustics", {"ir", "water", "runtime/reflection"}),
            gen("plan", {"ir", "water", "runtime/reflection"}),
            gen("toolchain", {"ir", "runtime/reflection"}),
            gen("pipeline", {"ir", "water", "caustics", "plan", "toolchain", "runtime/reflection"}),
        };
        std::set<std::string> below(generator.begin(), generator.end());
        for (const std::string& room : rooms) {
            below.insert("eval/" + room);
            v.push_back(Layer{"eval/" + room,
                              {"generator/eval/" + room, "generator/include/watergen/eval/" + room},
                              below});
        }
        below.insert("cli");
        v.push_back(Layer{"cli", {"generator/cli"}, below});
        return v;
    }();
    return all;
}

bool include_allowed(const std::set<std::string>& allowed, const std::string& path) {
    for (const auto& prefix : allowed)
        if (path.rfind(prefix + "/", 0) == 0 || path.rfind(prefix + ".h", 0) == 0) return true;
    return false;
}

// The layer a folder belongs to: the one with the longest folder that contains it.
const Layer* layer_of(const std::string& folder) {
    const Layer* best = nullptr;
    size_t best_length = 0;
    for (const Layer& l : layers())
        for (const std::string& f : l.folders)
            if ((folder == f || folder.rfind(f + "/", 0) == 0) && f.size() > best_length) {
                best = &l;
                best_length = f.size();
            }
    return best;
}

// Every folder below `top` (relative to the source root) that holds a file.
std::set<std::string> folders_with_files(const fs::path& root, const std::string& top) {
    std::set<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(root / top))
        if (e.is_regular_file())
            out.insert(fs::relative(e.path().parent_path(), root).generic_string());
    return out;
}

} // namespace

TEST_CASE("every_source_folder_belongs_to_a_layer", "[layout]") {
    const fs::path root = source_dir();
    size_t folders = 0;
    for (const char* top : {"generator", "runtime"})
        for (const std::string& folder : folders_with_files(root, top)) {
            // Build files only.
            if (folder == "generator" || folder == "runtime" || folder == "generator/eval")
                continue;
            ++folders;
            INFO(folder << " is in no layer: add it to the layers of tests/layout and to "
                           "docs/layout.md");
            CHECK(layer_of(folder) != nullptr);
        }
    CHECK(folders > 20);
}

TEST_CASE("layers_include_only_the_layers_they_may_use", "[layout]") {
    const fs::path root = source_dir();
    const std::regex include_re(R"re(#include\s+"watergen/([^"]+)")re");
    size_t files = 0;
    for (const char* top : {"generator", "runtime"})
        for (const auto& e : fs::recursive_directory_iterator(root / top)) {
            if (!e.is_regular_file()) continue;
            const std::string folder = fs::relative(e.path().parent_path(), root).generic_string();
            const Layer* layer = layer_of(folder);
            if (layer == nullptr) continue; // every_source_folder_belongs_to_a_layer fails
            const std::string text = read_text(e.path());
            ++files;
            for (std::sregex_iterator it(text.begin(), text.end(), include_re), end; it != end;
                 ++it) {
                const std::string included = (*it)[1];
                INFO(e.path().string()
                     << " (" << layer->name << ") includes watergen/" << included);
                CHECK(include_allowed(layer->may_include, included));
            }
        }
    CHECK(files > 150);
}

TEST_CASE("include_rules_catch_an_upward_include", "[layout]") {
    // The rule the test above applies, on includes a wrong edit would add.
    auto allowed = [](const std::string& folder, const std::string& include) {
        const Layer* l = layer_of(folder);
        REQUIRE(l != nullptr);
        return include_allowed(l->may_include, include);
    };
    CHECK_FALSE(allowed("generator/ir", "water/water_shader.h"));
    CHECK_FALSE(allowed("generator/pipeline", "eval/draw/variant_render.h"));
    CHECK_FALSE(allowed("generator/eval/scene", "eval/draw/caustics_pass_draw.h"));
    CHECK_FALSE(allowed("runtime/src", "ir/ir.h"));
    CHECK_FALSE(allowed("runtime/src", "headless/headless_device.h"));
    CHECK_FALSE(allowed("runtime/headless", "runner/vulkan_runner.h"));
    CHECK_FALSE(allowed("runtime/headless", "ir/ir.h"));
    CHECK_FALSE(allowed("runtime/runner", "eval/probe/probe.h"));
    CHECK(allowed("runtime/headless", "runtime/variant_pipeline.h"));
    CHECK(allowed("runtime/runner", "headless/offscreen_draw.h"));
    CHECK(allowed("generator/eval/draw", "runner/vulkan_runner.h"));
    CHECK(allowed("generator/eval/compare", "eval/report/compare_report.h"));
    CHECK(allowed("generator/water/nodes", "ir/dsl.h"));
    CHECK(layer_of("generator/include/watergen/eval/draw")->name == "eval/draw");
    CHECK(layer_of("generator/somewhere_new") == nullptr);
}

TEST_CASE("every_generator_layer_has_its_public_header_folder_and_nothing_else_does", "[layout]") {
    const fs::path gen = source_dir() / "generator";
    std::set<std::string> sources, headers;
    for (const Layer& l : layers()) {
        // No public generator headers: the CLI and the runtime's layers.
        if (l.name == "cli" || l.folders.front().rfind("runtime/", 0) == 0) continue;
        for (const std::string& f : l.folders)
            (f.find("/include/") != std::string::npos ? headers : sources).insert(l.name);
    }
    std::set<std::string> source_folders, header_folders;
    for (const auto& e : fs::directory_iterator(gen))
        if (e.is_directory() && e.path().filename() != "include" && e.path().filename() != "cli" &&
            e.path().filename() != "eval")
            source_folders.insert(e.path().filename());
    for (const auto& e : fs::directory_iterator(gen / "eval"))
        if (e.is_directory()) source_folders.insert("eval/" + e.path().filename().string());
    for (const auto& e : fs::directory_iterator(gen / "include" / "watergen")) {
        if (!e.is_directory()) {
            FAIL_CHECK("a header outside every layer folder: " << e.path());
            continue;
        }
        if (e.path().filename() != "eval") header_folders.insert(e.path().filename());
    }
    for (const auto& e : fs::directory_iterator(gen / "include" / "watergen" / "eval"))
        if (e.is_directory())
            header_folders.insert("eval/" + e.path().filename().string());
        else
            FAIL_CHECK("a header outside every room: " << e.path());
    CHECK(source_folders == sources);
    CHECK(header_folders == headers);
}

TEST_CASE("layout_table_names_every_folder", "[layout]") {
    const fs::path root = source_dir();
    const std::string doc = read_text(root / "docs" / "layout.md");
    const size_t start = doc.find("| folder |");
    REQUIRE(start != std::string::npos);
    const std::string table = doc.substr(start, doc.find("\n\n", start) - start);
    std::set<std::string> listed;
    const std::regex row_re(R"re(\n\| `([a-z_./]+?)/?` \|)re");
    for (std::sregex_iterator it(table.begin(), table.end(), row_re), end; it != end; ++it)
        listed.insert((*it)[1]);
    std::set<std::string> folders;
    for (const auto& e : fs::directory_iterator(root / "generator"))
        if (e.is_directory() && e.path().filename() != "include" && e.path().filename() != "eval")
            folders.insert("generator/" + e.path().filename().string());
    for (const auto& e : fs::directory_iterator(root / "generator" / "eval"))
        if (e.is_directory()) folders.insert("generator/eval/" + e.path().filename().string());
    for (const auto& e : fs::directory_iterator(root / "runtime"))
        if (e.is_directory() && e.path().filename() != "include")
            folders.insert("runtime/" + e.path().filename().string());
    for (const char* top : {"cmake", "templates", "examples", "generated", "docs", "scripts"})
        folders.insert(top);
    for (const auto& e : fs::directory_iterator(root / "tests"))
        if (e.is_directory()) folders.insert("tests/" + e.path().filename().string());
    CHECK(listed == folders);
}
