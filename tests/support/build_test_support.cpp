#include "build_test_support.h"

#include "watergen/pipeline/build_output.h"

namespace watergen::test {

std::map<std::string, std::string> reference_build() {
    static const std::map<std::string, std::string> tree = [] {
        Diagnostics ds;
        auto material = load_material(source_dir() + "/examples/materials/default.json", ds);
        REQUIRE(material);
        const TempDir tmp("reference");
        BuildRequest r{*material, example_scenes(), tmp.path / "out", {}};
        REQUIRE(build_material(r).ok());
        return read_tree(r.out);
    }();
    return tree;
}

} // namespace watergen::test
