// The counting workers' protocol (cost_worker.h): the argv a job is sent as, which the
// `watergen cost` and `watergen pick` hidden flags read back; and a worker run outside valgrind
// refuses before it touches a device.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>

#include "watergen/eval/measure/cost_worker.h"

using namespace watergen;

namespace {

// The value after `flag`, "" when absent; every value after each occurrence in *all.
std::string value_of(const std::vector<std::string>& argv, const std::string& flag,
                     std::vector<std::string>* all = nullptr) {
    std::string first;
    for (size_t i = 0; i + 1 < argv.size(); ++i)
        if (argv[i] == flag) {
            if (first.empty()) first = argv[i + 1];
            if (all) all->push_back(argv[i + 1]);
        }
    return first;
}

bool has(const std::vector<std::string>& argv, const std::string& word) {
    return std::find(argv.begin(), argv.end(), word) != argv.end();
}

} // namespace

TEST_CASE("a_variant_count_job_goes_to_watergen_cost_counted", "[cost]") {
    VariantCountJob job;
    job.keys = {"fresnel=schlick", "fresnel=exact", "fresnel=schlick"};
    job.size = 16;
    job.preset = "muddy_river";
    job.view = "sun_glint";
    job.unroll = LoopUnroll::None;
    job.strict_half = true;
    const auto argv = count_worker_argv(job, "/opt/bin/watergen");
    REQUIRE(argv.size() > 4);
    CHECK(std::vector<std::string>(argv.begin(), argv.begin() + 3) ==
          std::vector<std::string>{"/opt/bin/watergen", "cost", "--counted"});
    CHECK(value_of(argv, "--size") == "16");
    std::vector<std::string> keys;
    value_of(argv, "--key", &keys);
    CHECK(keys == job.keys); // a key given twice is sent twice: the A/A pair
    CHECK(value_of(argv, "--preset") == "muddy_river");
    CHECK(value_of(argv, "--view") == "sun_glint");
    CHECK(value_of(argv, "--unroll") == "none");
    CHECK(has(argv, "--strict-half"));
    // A mesh variant's grid and tessellation factor, so the worker draws what was measured.
    CHECK(value_of(argv, "--grid-rings") == "32");
    job.grid = {0.25, 64, 5};
    job.tess_max = 16;
    const auto mesh = count_worker_argv(job, "watergen");
    CHECK(value_of(mesh, "--grid-spacing") == "0.25");
    CHECK(value_of(mesh, "--grid-rings") == "64");
    CHECK(value_of(mesh, "--grid-levels") == "5");
    CHECK(value_of(mesh, "--tess-max") == "16");
    // Every axis of the variant, so the worker's own variant flags read it back.
    for (size_t a = 0; a < axes().size(); ++a)
        CHECK(value_of(argv, "--" + axes()[a].name) == job.variant.choices[a]);
    VariantCountJob plain;
    const auto defaults = count_worker_argv(plain, "watergen");
    CHECK_FALSE(has(defaults, "--preset"));
    CHECK_FALSE(has(defaults, "--strict-half"));
    CHECK_FALSE(has(defaults, "--key"));
    CHECK(value_of(defaults, "--unroll") == "hinted");
}

TEST_CASE("a_material_count_job_sends_absolute_paths", "[cost]") {
    // The worker runs in a scratch directory of its own: relative paths would not resolve.
    const MaterialCountJob job{"materials/m.json", "scenes/s.json", false, 8, {"fresnel=exact"}};
    const auto argv = count_worker_argv(job, "watergen");
    // The material right after the subcommand: --scene takes every word up to the next flag,
    // so it comes last, with its one value.
    CHECK(std::vector<std::string>(argv.begin(), argv.begin() + 6) ==
          std::vector<std::string>{"watergen", "pick",
                                   std::filesystem::absolute("materials/m.json").string(),
                                   "--counted", "--cost-size", "8"});
    CHECK(std::vector<std::string>(argv.end() - 2, argv.end()) ==
          std::vector<std::string>{"--scene", std::filesystem::absolute("scenes/s.json").string()});
    CHECK(has(argv, "--unfolded"));
    CHECK(value_of(argv, "--key") == "fresnel=exact");
    const auto built_in = count_worker_argv(MaterialCountJob{"", "", true, 64, {}}, "watergen");
    CHECK(built_in == std::vector<std::string>{"watergen", "pick", "--counted", "--cost-size", "64",
                                               "--grid-spacing", "0.5", "--grid-rings", "32",
                                               "--grid-levels", "8"});
    // A mesh candidate's grid goes along (before --scene, which takes the words after it).
    MaterialCountJob mesh = job;
    mesh.grid = {0.25, 16, 4};
    const auto with_grid = count_worker_argv(mesh, "watergen");
    CHECK(value_of(with_grid, "--grid-spacing") == "0.25");
    CHECK(value_of(with_grid, "--grid-rings") == "16");
    CHECK(value_of(with_grid, "--grid-levels") == "4");
    CHECK(with_grid[with_grid.size() - 2] == "--scene");
}

TEST_CASE("a_worker_outside_valgrind_refuses_before_any_device", "[cost]") {
    VariantCountJob job;
    job.keys = {"fresnel=exact"};
    const CountWorkerRun run = run_count_worker(job);
    CHECK(run.status == RunStatus::BadInput);
    CHECK(run.error == "--counted is the worker of watergen cost and runs under valgrind "
                       "--tool=callgrind");
    const CountWorkerRun pick = run_count_worker(MaterialCountJob{}, default_material(), nullptr);
    CHECK(pick.status == RunStatus::BadInput);
    CHECK(pick.error.find("worker of watergen pick") != std::string::npos);
}
