// manifest.json as an engine's runtime (watergen::runtime) reads it: ShaderBuild::open, then
// what an engine asks of the build it opened (select by a variant's choices and key, the bytes
// of its files). Whatever the bytes, open() returns a build or an error naming the manifest,
// never both, never neither; a variant's files (absent: only the manifest is written) are
// errors, never a crash.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "fuzz_build_dir.h"
#include "watergen/runtime/shader_build.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace watergen;
    static const fuzz::BuildDir dir("manifest");
    dir.write("manifest.json", data, size);
    std::string error;
    const auto build = ShaderBuild::open(dir.path, &error);
    if (!build) {
        if (error.rfind((dir.path / "manifest.json").string() + ": ", 0) != 0) std::abort();
        return 0;
    }
    if (!error.empty()) std::abort(); // a build and an error
    for (const BuildVariant& v : build->variants()) {
        (void)build->select(v.scene, v.choices, Fallback::NearestKept);
        (void)build->select_key(v.scene, v.key);
        // The listed files do not exist here: each is an error naming the file, or the
        // manifest's refusal of a path outside the build.
        std::string why;
        if (build->spirv(v, "glsl", ShaderStage::Fragment, &why) || why.empty()) std::abort();
        why.clear();
        if (build->reflection(v, "glsl", ShaderStage::Vertex, &why) || why.empty()) std::abort();
    }
    return 0;
}
