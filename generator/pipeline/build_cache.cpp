#include "watergen/pipeline/build_cache.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>
#include <unistd.h>

#include <glslang/build_info.h>
#include <spirv-tools/libspirv.h>
#include <spirv_cross/spirv_cross_c.h>
#include <xxhash.h>

namespace watergen {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMagic = "watergen-cache 1\n";

std::string hex16(uint64_t h) {
    char s[17];
    std::snprintf(s, sizeof s, "%016llx", static_cast<unsigned long long>(h));
    return s;
}

} // namespace

const std::string& toolchain_fingerprint() {
    static const std::string text = std::string("watergen ") + WATERGEN_VERSION + "; glslang " +
                                    std::to_string(GLSLANG_VERSION_MAJOR) + "." + std::to_string(GLSLANG_VERSION_MINOR) +
                                    "." + std::to_string(GLSLANG_VERSION_PATCH) + "; SPIRV-Tools " +
                                    spvSoftwareVersionString() + "; SPIRV-Cross C API " +
                                    std::to_string(SPVC_C_API_VERSION_MAJOR) + "." + std::to_string(SPVC_C_API_VERSION_MINOR) +
                                    "." + std::to_string(SPVC_C_API_VERSION_PATCH);
    return text;
}

std::string content_hash(const std::vector<std::string>& parts) {
    XXH64_state_t* state = XXH64_createState();
    XXH64_reset(state, 0);
    auto feed = [&](const std::string& s) {
        const uint64_t n = s.size();
        XXH64_update(state, &n, sizeof n);
        XXH64_update(state, s.data(), s.size());
    };
    feed(toolchain_fingerprint());
    for (const auto& p : parts) feed(p);
    const uint64_t h = XXH64_digest(state);
    XXH64_freeState(state);
    return hex16(h);
}

fs::path BuildCache::entry(const std::string& hash) const { return dir_ / hash.substr(0, 2) / (hash + ".wgc"); }

std::optional<FileMap> BuildCache::load(const std::string& hash) const {
    if (!enabled()) return std::nullopt;
    std::ifstream in(entry(hash), std::ios::binary);
    if (!in) return std::nullopt;
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string data = ss.str();
    const std::string magic = kMagic;
    if (data.compare(0, magic.size(), magic) != 0) return std::nullopt;
    // Records: "<path>\n<size>\n<bytes>".
    FileMap files;
    size_t pos = magic.size();
    while (pos < data.size()) {
        const size_t nl1 = data.find('\n', pos);
        if (nl1 == std::string::npos) return std::nullopt;
        const size_t nl2 = data.find('\n', nl1 + 1);
        if (nl2 == std::string::npos) return std::nullopt;
        const std::string path = data.substr(pos, nl1 - pos);
        char* end = nullptr;
        const std::string size_text = data.substr(nl1 + 1, nl2 - nl1 - 1);
        const unsigned long long size = std::strtoull(size_text.c_str(), &end, 10);
        if (size_text.empty() || *end != '\0' || nl2 + 1 + size > data.size()) return std::nullopt;
        files[path] = data.substr(nl2 + 1, size);
        pos = nl2 + 1 + size;
    }
    if (files.empty()) return std::nullopt;
    return files;
}

std::optional<std::string> BuildCache::store(const std::string& hash, const FileMap& files) const {
    if (!enabled()) return std::nullopt;
    std::string data = kMagic;
    for (const auto& [path, bytes] : files) data += path + "\n" + std::to_string(bytes.size()) + "\n" + bytes;
    const fs::path target = entry(hash);
    std::error_code ec;
    fs::create_directories(target.parent_path(), ec);
    if (ec) return "cannot create " + target.parent_path().string() + ": " + ec.message();
    // Unique per process and thread: two jobs may store the same entry at once.
    static std::atomic<unsigned> counter{0};
    const fs::path tmp = target.string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                         std::to_string(std::hash<std::thread::id>{}(std::this_thread::get_id())) + "-" +
                         std::to_string(counter++);
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out.write(data.data(), static_cast<std::streamsize>(data.size()));
        if (!out) {
            fs::remove(tmp, ec);
            return "cannot write " + tmp.string();
        }
    }
    fs::rename(tmp, target, ec);
    if (ec) {
        fs::remove(tmp, ec);
        return "cannot rename into " + target.string();
    }
    return std::nullopt;
}

fs::path default_cache_dir() {
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return fs::path(xdg) / "watergen";
    if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "watergen";
    return {};
}

} // namespace watergen
