// A shard's shard.json and manifest.json as a hostile shard may hold them: the input is the
// shard.json text, a NUL byte, then the manifest text. Whatever the bytes, a shard the checks
// accept has every variant in its key range and among shard.json's shapes, and names only files
// shard.json lists, inside their directories.
#include <cstdint>
#include <cstdlib>
#include <set>
#include <string>

#include "watergen/pipeline/manifest/manifest_files.h"
#include "watergen/pipeline/output/output_writer.h"
#include "watergen/pipeline/shards/shard_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace watergen;
    const std::string input(reinterpret_cast<const char*>(data), size);
    const size_t nul = input.find('\0');
    const std::string shard_text_bytes = input.substr(0, nul);
    const std::string manifest_bytes = nul == std::string::npos ? "" : input.substr(nul + 1);
    std::string why;
    const auto shard = parse_shard_file(shard_text_bytes, &why);
    if (!shard) {
        if (why.empty()) std::abort(); // a refusal always says why
        return 0;
    }
    if (shard->shard.index < 1 || shard->shard.index > shard->shard.count) std::abort();
    std::set<std::string> listed;
    for (size_t i = 0; i < shard->files.size(); ++i) {
        const ListedFile f = shard->files[i];
        if (!is_plain_relative_path(f.path) || !shard->lists(f.path)) std::abort();
        listed.insert(f.path);
    }
    const auto manifest = nlohmann::ordered_json::parse(manifest_bytes, nullptr, false);
    if (!check_shard_manifest(manifest, *shard).empty()) return 0;
    for (const auto& v : manifest["variants"]) {
        if (!in_shard(shard->shard, v["key"].get<std::string>())) std::abort();
        std::vector<std::string> paths;
        if (!named_files(v, paths).empty()) std::abort();
        for (const std::string& p : paths)
            if (!listed.count(p) || !is_plain_relative_path(p)) std::abort();
    }
    return 0;
}
