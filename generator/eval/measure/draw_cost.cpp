#include "watergen/eval/measure/draw_cost.h"

#include <algorithm>
#include <future>
#include <thread>
#include <tuple>

#include "watergen/eval/measure/draw_count.h"

namespace watergen {

namespace {

std::vector<std::string> keys_of(const std::vector<Variant>& variants) {
    std::vector<std::string> keys;
    for (const Variant& v : variants)
        keys.push_back(v.key());
    return keys;
}

std::optional<std::map<std::string, uint64_t>>
count_in_parallel(const std::vector<Variant>& v, const KeyedWorker& worker, std::string* error) {
    return count_keys_in_parallel(keys_of(v), worker, std::filesystem::temp_directory_path(),
                                  std::max(1u, std::thread::hardware_concurrency()), error);
}

// The smallest count of a path over the runs, and by how much the runs differ (percent).
std::pair<uint64_t, double> spread(const std::vector<uint64_t>& v) {
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    const double d = static_cast<double>(*hi - *lo);
    return {*lo, *lo ? 100.0 * d / static_cast<double>(*lo) : 0.0};
}

} // namespace

std::optional<std::map<std::string, uint64_t>>
count_draw_costs(const std::vector<Variant>& variants, uint32_t size, const std::string& preset,
                 const std::string& view, std::string* error, bool strict_half,
                 const WaterGridDesc& grid) {
    const std::filesystem::path executable = own_executable();
    return count_in_parallel(
        variants,
        [&](const std::vector<std::string>& part) {
            VariantCountJob job;
            job.keys = part;
            job.size = size;
            job.preset = preset;
            job.view = view;
            job.strict_half = strict_half;
            job.grid = grid;
            return count_worker_argv(job, executable);
        },
        error);
}

std::optional<std::map<std::string, uint64_t>>
count_material_costs(const std::string& material_path, const std::string& scene_path,
                     const std::vector<Variant>& variants, uint32_t size, std::string* error,
                     bool folded, const WaterGridDesc& grid) {
    const std::filesystem::path executable = own_executable();
    return count_in_parallel(
        variants,
        [&](const std::vector<std::string>& part) {
            return count_worker_argv(
                MaterialCountJob{material_path, scene_path, folded, size, part, grid}, executable);
        },
        error);
}

std::optional<std::vector<std::map<std::string, uint64_t>>>
count_jobs(const std::vector<VariantCountJob>& jobs, std::string* error) {
    const std::filesystem::path executable = own_executable();
    const size_t at_once = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::map<std::string, uint64_t>> out;
    for (size_t first = 0; first < jobs.size(); first += at_once) {
        std::vector<std::future<DrawCountRun>> runs;
        for (size_t i = first; i < std::min(jobs.size(), first + at_once); ++i)
            runs.push_back(std::async(std::launch::async, [&, i] {
                return count_draws_under_valgrind(count_worker_argv(jobs[i], executable),
                                                  std::filesystem::temp_directory_path());
            }));
        // Every run is waited for before an error returns: none outlives the call.
        std::vector<DrawCountRun> done;
        for (auto& run : runs)
            done.push_back(run.get());
        for (const DrawCountRun& run : done) {
            const auto counts = steady_draw_counts(run, error);
            if (!counts) return std::nullopt;
            out.push_back(*counts);
        }
    }
    return out;
}

VariantCost count_variant_cost(const VariantCountJob& job, uint32_t runs,
                               const std::filesystem::path& scratch) {
    VariantCost out;
    std::map<std::string, std::vector<uint64_t>> counts;
    const std::vector<std::string> argv = count_worker_argv(job, own_executable());
    for (uint32_t run = 0; run < runs; ++run) {
        const DrawCountRun r = count_draws_under_valgrind(argv, scratch);
        if (!r.ok()) {
            out.error = r.error;
            return out;
        }
        for (const auto& c : r.counts)
            counts[c.label].push_back(c.instructions);
    }
    for (size_t i = 0; i < 2; ++i) {
        const std::string path = i == 0 ? "glsl" : "hlsl";
        const auto& draw = counts[path];
        const auto& first = counts[path + " first"];
        if (draw.empty() || first.empty()) continue;
        PathCost c;
        std::tie(c.draw, c.draw_spread) = spread(draw);
        std::tie(c.first, c.first_spread) = spread(first);
        out.paths[i] = c;
    }
    return out;
}

} // namespace watergen
