// Build cache entries as another process (or an attacker) may have left them in a shared
// cache. The input is either a whole entry, or edits (offset, byte) applied to a valid entry.
// Whatever the bytes, a hit returns exactly the expected files with plain relative names, and
// a rejected entry is gone afterwards; nothing is written outside the cache directory.
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "watergen/pipeline/cache/build_cache.h"

namespace fs = std::filesystem;

namespace {

const std::string kHash = "0123456789abcdef";
const std::vector<std::string> kExpected = {"glsl/water.frag.glsl", "glsl/water.frag.spv",
                                            "variant.json"};

// A directory of this process's own, removed when the fuzzer exits.
struct WorkDir {
    fs::path path =
        fs::temp_directory_path() / ("watergen-cache-fuzz-" + std::to_string(::getpid()));
    WorkDir() { fs::create_directories(path); }
    ~WorkDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

const fs::path& work_dir() {
    static const WorkDir dir;
    return dir.path;
}

std::string valid_entry(const watergen::BuildCache& cache) {
    watergen::FileMap files = {{"glsl/water.frag.glsl", "#version 450\nvoid main() {}\n"},
                               {"glsl/water.frag.spv", std::string("\x03\x02\x23\x07\0\0\1\0", 8)},
                               {"variant.json", "{\"key\": \"fresnel=schlick\"}\n"}};
    cache.store(kHash, files);
    std::string bytes;
    if (FILE* f = std::fopen(cache.entry(kHash).c_str(), "rb")) {
        char buf[4096];
        for (size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;)
            bytes.append(buf, n);
        std::fclose(f);
    }
    return bytes;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace watergen;
    const BuildCache cache(work_dir() / "cache");
    std::string entry;
    if (size > 0 && data[0] % 2 == 0) {
        entry.assign(reinterpret_cast<const char*>(data + 1), size - 1);
    } else {
        entry = valid_entry(cache);
        for (size_t i = 1; i + 2 < size; i += 3) {
            const size_t at = (size_t(data[i]) << 8 | data[i + 1]) % (entry.size() + 1);
            if (data[i + 2] == 0xFF)
                entry.erase(at, 1);
            else
                entry.insert(at, 1, static_cast<char>(data[i + 2]));
        }
    }
    fs::create_directories(cache.entry(kHash).parent_path());
    if (FILE* f = std::fopen(cache.entry(kHash).c_str(), "wb")) {
        std::fwrite(entry.data(), 1, entry.size(), f);
        std::fclose(f);
    }
    const CacheLookup lookup = cache.load(kHash, kExpected);
    if (lookup.files) {
        if (!lookup.rejected.empty() || lookup.files->size() != kExpected.size()) std::abort();
        for (const auto& name : kExpected)
            if (!lookup.files->count(name)) std::abort();
    } else if (!lookup.rejected.empty() && fs::exists(cache.entry(kHash))) {
        std::abort(); // a rejected entry is evicted
    }
    return 0;
}
