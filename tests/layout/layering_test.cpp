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

// The layers cut into rooms: generator/<house>/<room>, their headers in
// generator/include/watergen/<house>/<room>; a room uses the rooms before it in its house.
struct House {
    std::string name;
    std::vector<std::string> rooms;
};
const std::vector<House>& houses() {
    static const std::vector<House> all = {
        {"ir", {"core", "emit", "cpu", "fold"}},
        {"pipeline",
         {"output", "cache", "variant", "jobs", "manifest", "record", "shards", "build"}},
        {"eval", {"image", "scene", "draw", "measure", "probe", "report", "compare", "bench"}},
    };
    return all;
}
bool is_house(const std::string& name) {
    for (const House& h : houses())
        if (h.name == name) return true;
    return false;
}

// Generic first. The runtime: the engine library (runtime/src) includes only itself; the
// headless device (runtime/headless) the runtime and itself; the test runner (runtime/runner)
// those and itself; nothing in runtime/ includes the generator. runtime/reflection.h is the
// shader interface types every layer shares, runtime/host_values.h the values every packer
// computes on the host; runtime/manifest_schema.h the keys of manifest.json,
// which the pipeline's rooms write, merge and read back as the runtime reads them. The IR's rooms
// use the rooms before them; the layers above the IR may use all of it. The pipeline's rooms use
// the layers above the pipeline and the rooms before them; the evaluation rooms
// (generator/eval/<room>) the whole generator, the runtime's three layers and the rooms before
// them; the CLI uses everything.
const std::vector<Layer>& layers() {
    static const std::vector<Layer> all = [] {
        auto gen = [](const std::string& name, std::set<std::string> uses) {
            uses.insert(name);
            return Layer{
                name, {"generator/" + name, "generator/include/watergen/" + name}, std::move(uses)};
        };
        auto rooms = [&](std::vector<Layer>& v, const std::string& house,
                         std::set<std::string> below) {
            for (const House& h : houses())
                if (h.name == house)
                    for (const std::string& room : h.rooms) {
                        below.insert(house + "/" + room);
                        v.push_back(gen(house + "/" + room, below));
                    }
        };
        std::vector<Layer> v = {
            Layer{"runtime", {"runtime/src", "runtime/include/watergen/runtime"}, {"runtime"}},
            Layer{"headless",
                  {"runtime/headless", "runtime/include/watergen/headless"},
                  {"runtime", "headless"}},
            Layer{"runner",
                  {"runtime/runner", "runtime/include/watergen/runner"},
                  {"runtime", "headless", "runner"}},
        };
        rooms(v, "ir", {"runtime/reflection", "runtime/host_values"});
        v.push_back(gen("water", {"ir", "runtime/reflection", "runtime/host_values"}));
        v.push_back(gen("caustics", {"ir", "water", "runtime/reflection", "runtime/host_values"}));
        v.push_back(gen("plan", {"ir", "water", "runtime/reflection", "runtime/host_values"}));
        v.push_back(gen("toolchain", {"ir", "runtime/reflection", "runtime/host_values"}));
        rooms(v, "pipeline",
              {"ir", "water", "caustics", "plan", "toolchain", "runtime/reflection",
               "runtime/host_values", "runtime/manifest_schema"});
        rooms(v, "eval",
              {"ir", "water", "caustics", "plan", "toolchain", "pipeline", "runtime", "headless",
               "runner"});
        std::set<std::string> everything;
        for (const Layer& l : v)
            everything.insert(l.name);
        everything.insert("cli");
        v.push_back(Layer{"cli", {"generator/cli"}, everything});
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
            if (folder == "generator" || folder == "runtime") continue;
            if (folder.rfind("generator/", 0) == 0 && is_house(folder.substr(10))) {
                for (const auto& e : fs::directory_iterator(root / folder))
                    if (e.is_regular_file()) {
                        INFO(e.path() << ": a house holds its rooms and its CMakeLists.txt only");
                        CHECK(e.path().filename() == "CMakeLists.txt");
                    }
                continue;
            }
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
    CHECK_FALSE(allowed("generator/ir/core", "water/water_shader.h"));
    CHECK_FALSE(allowed("generator/ir/core", "ir/emit/emitter.h"));
    CHECK_FALSE(allowed("generator/ir/cpu", "ir/fold/ir_fold.h"));
    CHECK(allowed("generator/ir/fold", "ir/cpu/cpu_evaluator.h"));
    CHECK_FALSE(allowed("generator/pipeline/build", "eval/draw/variant_render.h"));
    CHECK_FALSE(allowed("generator/pipeline/output", "pipeline/cache/build_cache.h"));
    CHECK_FALSE(allowed("generator/pipeline/shards", "pipeline/build/build_output.h"));
    CHECK(allowed("generator/pipeline/build", "pipeline/shards/sharded_build.h"));
    CHECK(allowed("generator/water", "ir/fold/ir_fold.h"));
    CHECK(layer_of("generator/ir") == nullptr);
    CHECK_FALSE(allowed("generator/eval/scene", "eval/draw/caustics_pass_draw.h"));
    CHECK_FALSE(allowed("runtime/src", "ir/ir.h"));
    CHECK_FALSE(allowed("runtime/src", "headless/headless_device.h"));
    CHECK_FALSE(allowed("runtime/headless", "runner/vulkan_runner.h"));
    CHECK_FALSE(allowed("runtime/headless", "ir/ir.h"));
    CHECK_FALSE(allowed("runtime/runner", "eval/probe/probe.h"));
    CHECK(allowed("runtime/headless", "runtime/variant_pipeline.h"));
    CHECK(allowed("generator/pipeline/output", "runtime/manifest_schema.h"));
    CHECK(allowed("generator/pipeline/shards", "runtime/manifest_schema.h"));
    CHECK_FALSE(allowed("generator/pipeline/manifest", "runtime/shader_build.h"));
    CHECK_FALSE(allowed("generator/plan", "runtime/manifest_schema.h"));
    CHECK(allowed("runtime/runner", "headless/offscreen_draw.h"));
    CHECK(allowed("generator/eval/draw", "runner/vulkan_runner.h"));
    CHECK(allowed("generator/eval/compare", "eval/report/compare_report.h"));
    CHECK(allowed("generator/water/nodes", "ir/core/dsl.h"));
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
            !is_house(e.path().filename()))
            source_folders.insert(e.path().filename());
    for (const auto& e : fs::directory_iterator(gen / "include" / "watergen")) {
        if (!e.is_directory()) {
            FAIL_CHECK("a header outside every layer folder: " << e.path());
            continue;
        }
        if (!is_house(e.path().filename())) header_folders.insert(e.path().filename());
    }
    for (const House& h : houses()) {
        for (const auto& e : fs::directory_iterator(gen / h.name))
            if (e.is_directory())
                source_folders.insert(h.name + "/" + e.path().filename().string());
        for (const auto& e : fs::directory_iterator(gen / "include" / "watergen" / h.name))
            if (e.is_directory())
                header_folders.insert(h.name + "/" + e.path().filename().string());
            else
                FAIL_CHECK("a header outside every room: " << e.path());
    }
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
        if (e.is_directory() && e.path().filename() != "include" && !is_house(e.path().filename()))
            folders.insert("generator/" + e.path().filename().string());
    for (const House& h : houses())
        for (const auto& e : fs::directory_iterator(root / "generator" / h.name))
            if (e.is_directory())
                folders.insert("generator/" + h.name + "/" + e.path().filename().string());
    for (const auto& e : fs::directory_iterator(root / "runtime"))
        if (e.is_directory() && e.path().filename() != "include")
            folders.insert("runtime/" + e.path().filename().string());
    for (const char* top : {"cmake", "templates", "examples", "generated", "docs", "scripts"})
        folders.insert(top);
    for (const auto& e : fs::directory_iterator(root / "tests"))
        if (e.is_directory()) folders.insert("tests/" + e.path().filename().string());
    CHECK(listed == folders);
}

TEST_CASE("no_source_folder_holds_more_than_15_cpp_files", "[layout]") {
    // A folder of more is a room that wants cutting. The CLI, one file per command, is the
    // exception.
    const fs::path root = source_dir();
    for (const char* top : {"generator", "runtime"})
        for (const std::string& folder : folders_with_files(root, top)) {
            if (folder == "generator/cli") continue;
            size_t cpp = 0;
            for (const auto& e : fs::directory_iterator(root / folder))
                if (e.is_regular_file() && e.path().extension() == ".cpp") ++cpp;
            INFO(folder << " holds " << cpp << " .cpp files");
            CHECK(cpp <= 15);
        }
}
