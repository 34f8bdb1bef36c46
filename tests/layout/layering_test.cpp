// The house as the README draws it: generator layers use only the layers above them, every
// layer has its public header folder, and the README's layout table names every folder.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

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

// What each generator layer may include (README "Layout"); runtime/reflection.h is the shader
// interface types every layer shares.
const std::map<std::string, std::set<std::string>>& allowed_includes() {
    static const std::map<std::string, std::set<std::string>> allowed = {
        {"ir", {"ir", "runtime/reflection"}},
        {"water", {"ir", "water", "runtime/reflection"}},
        {"caustics", {"ir", "water", "caustics", "runtime/reflection"}},
        {"plan", {"ir", "water", "plan", "runtime/reflection"}},
        {"toolchain", {"ir", "toolchain", "runtime/reflection"}},
        {"pipeline",
         {"ir", "water", "caustics", "plan", "toolchain", "pipeline", "runtime/reflection"}},
        {"render",
         {"ir", "water", "caustics", "plan", "toolchain", "pipeline", "render", "runtime"}},
        {"cli", {"ir", "water", "caustics", "plan", "toolchain", "pipeline", "render", "runtime"}},
    };
    return allowed;
}

bool include_allowed(const std::set<std::string>& allowed, const std::string& path) {
    for (const auto& prefix : allowed)
        if (path.rfind(prefix + "/", 0) == 0 || path.rfind(prefix + ".h", 0) == 0) return true;
    return false;
}

} // namespace

TEST_CASE("generator_layers_include_only_the_layers_above_them", "[layout]") {
    const fs::path gen = source_dir() / "generator";
    const std::regex include_re(R"re(#include\s+"watergen/([^"]+)")re");
    size_t files = 0;
    for (const auto& [layer, allowed] : allowed_includes()) {
        for (const fs::path& root : {gen / layer, gen / "include" / "watergen" / layer}) {
            if (!fs::exists(root)) continue;
            for (const auto& e : fs::recursive_directory_iterator(root)) {
                if (!e.is_regular_file()) continue;
                const std::string text = read_text(e.path());
                ++files;
                for (std::sregex_iterator it(text.begin(), text.end(), include_re), end; it != end;
                     ++it) {
                    const std::string included = (*it)[1];
                    INFO(e.path().string() << " includes watergen/" << included);
                    CHECK(include_allowed(allowed, included));
                }
            }
        }
    }
    CHECK(files > 100);
}

TEST_CASE("every_layer_has_its_public_header_folder_and_nothing_else_does", "[layout]") {
    const fs::path gen = source_dir() / "generator";
    std::set<std::string> layers, header_folders;
    for (const auto& e : fs::directory_iterator(gen))
        if (e.is_directory() && e.path().filename() != "include")
            layers.insert(e.path().filename());
    for (const auto& e : fs::directory_iterator(gen / "include" / "watergen"))
        if (e.is_directory())
            header_folders.insert(e.path().filename());
        else
            FAIL_CHECK("a header outside every layer folder: " << e.path());
    layers.erase("cli"); // the command has no public headers
    CHECK(layers == header_folders);
    std::set<std::string> known;
    for (const auto& [layer, allowed] : allowed_includes())
        known.insert(layer);
    known.erase("cli");
    CHECK(layers == known);
}

TEST_CASE("readme_layout_table_names_every_folder", "[layout]") {
    const fs::path root = source_dir();
    const std::string readme = read_text(root / "README.md");
    const size_t start = readme.find("## Layout");
    REQUIRE(start != std::string::npos);
    const std::string table = readme.substr(start, readme.find("\n## ", start + 1) - start);
    std::set<std::string> listed;
    const std::regex row_re(R"re(\n\| `([a-z_./]+?)/?` \|)re");
    for (std::sregex_iterator it(table.begin(), table.end(), row_re), end; it != end; ++it)
        listed.insert((*it)[1]);
    std::set<std::string> folders;
    for (const auto& e : fs::directory_iterator(root / "generator"))
        if (e.is_directory() && e.path().filename() != "include")
            folders.insert("generator/" + e.path().filename().string());
    for (const char* top : {"runtime", "cmake", "templates", "examples", "generated", "tests"})
        folders.insert(top);
    CHECK(listed == folders);
    std::set<std::string> test_folders;
    for (const auto& e : fs::directory_iterator(root / "tests"))
        if (e.is_directory()) test_folders.insert(e.path().filename());
    for (const auto& t : test_folders) {
        INFO("tests/" << t << " is not named in the README's tests row");
        CHECK((table.find("`" + t + "`") != std::string::npos ||
               table.find("`tests/" + t + "`") != std::string::npos));
    }
}
