#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "commands.h"
#include "watergen/pipeline/output/output_writer.h"

namespace watergen::cli {

bool bench_succeeded(const Diagnostics& diagnostics, const std::string& error,
                     const Common& common) {
    if (has_errors(diagnostics)) {
        print_diagnostics(diagnostics, common);
        return false;
    }
    if (!error.empty()) {
        std::fprintf(stderr, "watergen: error: %s\n", error.c_str());
        return false;
    }
    return true;
}

std::string interval_text(const RatioInterval& r) {
    return fmt::format("{:.3f} [{:.3f}, {:.3f}]", r.ratio, r.lo, r.hi);
}

bool write_bench_files(const std::string& out, const std::string& stem, const std::string& csv,
                       const std::string& json) {
    namespace fs = std::filesystem;
    fs::create_directories(out);
    const fs::path dir = out;
    for (auto [name, text] : {std::pair{stem + ".csv", csv}, std::pair{stem + ".json", json}})
        if (auto e = write_file_atomically(dir / name, text)) {
            std::fprintf(stderr, "watergen: error: %s\n", e->c_str());
            return false;
        }
    std::printf("wrote %s and %s\n", (dir / (stem + ".csv")).string().c_str(),
                (dir / (stem + ".json")).string().c_str());
    return true;
}

} // namespace watergen::cli
