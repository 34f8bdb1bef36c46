// ACO's statistics through RADV's null device (gpu_cost.h), with the watergen executable as the
// worker: what a family reports per stage, the per-pixel estimate against the loops it kept, an
// alias's costs, and a radv abort that does not take the caller down.
//
// Golden numbers are Mesa 22.3.6's (Debian 12, the platform CI runs): ACO's output is
// deterministic for one driver version and changes with the next; the relations hold for any.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "covering_builds.h"
#include "geometry_variant.h"
#include "watergen/eval/measure/aco_worker.h"
#include "watergen/eval/measure/gpu_cost.h"
#include "watergen/toolchain/child_process.h"

using namespace watergen;

namespace {

const std::filesystem::path kWatergen = WATERGEN_EXECUTABLE;

Variant gerstner() {
    Variant v = default_variant();
    REQUIRE_FALSE(set_choice(v, "waves", "gerstner"));
    return v;
}

std::vector<TargetCosts> costs(const std::vector<std::string>& names, const VariantBuild& b,
                               LoopUnroll unroll = LoopUnroll::AsHinted) {
    std::string error;
    const auto targets = parse_gpu_targets(names, &error);
    REQUIRE(targets);
    auto runs = variant_gpu_costs(*targets, {&b}, {"v"}, std::filesystem::current_path(), unroll,
                                  kWatergen);
    for (const auto& r : runs) {
        INFO(r.run.error);
        REQUIRE(r.run.ok());
        REQUIRE(r.costs.size() == 2);
        for (const auto& c : r.costs)
            REQUIRE(c.ok());
    }
    return runs;
}

bool mesa_22_3_6(const TargetCosts& t) {
    return t.run.driver.rfind("Mesa 22.3.6", 0) == 0;
}

} // namespace

TEST_CASE("rdna2 compiles a Gerstner variant's two paths and reports every stage") {
    const VariantBuild b = build_variant(gerstner());
    REQUIRE(b.ok());
    const auto runs = costs({"rdna2"}, b);
    const TargetCosts& t = runs[0];
    CHECK(t.run.device.find("NAVI21") != std::string::npos);
    for (const PipelineGpuCost& c : t.costs) {
        const StageGpuCost* f = c.stage("fragment");
        REQUIRE(f);
        REQUIRE(c.stage("vertex"));
        CHECK(f->instructions > 100);
        CHECK(f->vgprs > 0);
        CHECK(f->waves_per_simd > 0);
        CHECK(f->code_bytes >= 4 * f->instructions); // 4- or 8-byte encodings
        // The 9-step search loop is written [[dont_unroll]]; the wave sums inside have a
        // count from data and are unrolled by the driver: one loop kept, weighted by 9.
        CHECK(f->loops == 1);
        REQUIRE(f->per_pixel);
        CHECK(*f->per_pixel > 4 * f->instructions);
        if (mesa_22_3_6(t)) {
            CHECK(f->instructions == 537);
            CHECK(f->vgprs == 56);
            CHECK(*f->per_pixel == 537 + 8 * 278); // the 278-instruction body 8 more times
        }
    }
    // The GLSL and HLSL paths of this variant reach the same machine code size.
    CHECK(t.costs[0].stage("fragment")->instructions == t.costs[1].stage("fragment")->instructions);
}

TEST_CASE("a mesh and a tessellated variant compile on rdna2 with their own stages") {
    // The grid's vertex input and, tessellated, quad patches and the tessellation feature: the
    // stages the runtime draws. RADV merges the vertex and control stages (gfx9 on).
    const VariantBuild mesh = build_variant(test::geometry_variant("mesh", "gerstner"));
    const VariantBuild tess = build_variant(test::geometry_variant("tessellated", "gerstner"));
    const VariantBuild pass = build_variant(test::geometry_variant("screen_pass", "gerstner"));
    REQUIRE(mesh.ok());
    REQUIRE(tess.ok());
    REQUIRE(pass.ok());
    const TargetCosts m = costs({"rdna2"}, mesh)[0];
    const TargetCosts t = costs({"rdna2"}, tess)[0];
    const TargetCosts p = costs({"rdna2"}, pass)[0];
    for (const TargetCosts* run : {&m, &t})
        for (const PipelineGpuCost& c : run->costs) {
            REQUIRE(c.stage("vertex"));
            REQUIRE(c.stage("fragment"));
            CHECK(c.stage("fragment")->instructions > 100);
        }
    for (const PipelineGpuCost& c : t.costs) {
        REQUIRE(c.stage("tess_evaluation"));
        CHECK(c.stage("tess_evaluation")->instructions > 100); // displaces the patch point
    }
    CHECK_FALSE(m.costs[0].stage("tess_evaluation"));
    // The mesh's vertex stage displaces the grid (the screen pass' draws a triangle); its
    // fragment stage has no surface search, so it is cheaper per pixel than the screen pass'.
    CHECK(m.costs[0].stage("vertex")->instructions > p.costs[0].stage("vertex")->instructions);
    CHECK(m.costs[0].fragment_cost() < p.costs[0].fragment_cost() / 4);
    if (mesa_22_3_6(m)) {
        CHECK(m.costs[0].stage("vertex")->instructions == 492);
        CHECK(m.costs[0].stage("fragment")->instructions == 431);
        CHECK(t.costs[0].stage("tess_evaluation")->instructions == 505);
    }
}

TEST_CASE("a variant compiled twice reports the same statistics") {
    const VariantBuild b = build_variant(gerstner());
    const auto a = costs({"gcn4"}, b), c = costs({"gcn4"}, b);
    for (size_t i = 0; i < 2; ++i)
        for (const auto& col : gpu_cost_columns())
            CHECK(a[0].costs[i].stage("fragment")->*col.value ==
                  c[0].costs[i].stage("fragment")->*col.value);
}

TEST_CASE("with every loop unrolled the static count is the per-pixel count; with none kept "
          "the estimate weights all four") {
    const Variant v = gerstner();
    const VariantBuild all = build_variant(v, nullptr, EmitOptions{false, {}, LoopUnroll::All});
    const VariantBuild none = build_variant(v, nullptr, EmitOptions{false, {}, LoopUnroll::None});
    const auto unrolled = costs({"rdna2"}, all, LoopUnroll::All);
    const auto kept = costs({"rdna2"}, none, LoopUnroll::None);
    const StageGpuCost* u = unrolled[0].costs[0].stage("fragment");
    const StageGpuCost* k = kept[0].costs[0].stage("fragment");
    CHECK(u->loops == 0);
    REQUIRE(u->per_pixel);
    CHECK(*u->per_pixel == u->instructions);
    CHECK(k->loops == 4);
    REQUIRE(k->per_pixel);
    // Kept loops are shorter code and more executed instructions than unrolled ones.
    CHECK(k->instructions < u->instructions);
    CHECK(*k->per_pixel > *u->per_pixel);
}

TEST_CASE("steamdeck is rdna2's ISA: its costs are rdna2's, and Van Gogh compiles the same") {
    const VariantBuild b = build_variant(gerstner());
    const auto runs = costs({"rdna2", "steamdeck"}, b);
    CHECK(runs[1].run.target.alias_of == "rdna2");
    CHECK(runs[0].costs[0].stage("fragment")->instructions ==
          runs[1].costs[0].stage("fragment")->instructions);
    // The APU itself, as RADV knows it.
    GpuTarget vangogh{"vangogh", "vangogh", "Van Gogh", ""};
    std::vector<AcoPipelineSource> sources = {aco_source(b.languages[0], "v")};
    const auto apu =
        compile_on_targets({vangogh}, sources, std::filesystem::current_path(), 1, kWatergen);
    REQUIRE(apu[0].ok());
    const auto cost = gpu_cost(apu[0].pipelines[0], emitted_loops(b.shader.fragment));
    CHECK(cost.stage("fragment")->instructions == runs[0].costs[0].stage("fragment")->instructions);
    CHECK(cost.stage("fragment")->vgprs == runs[0].costs[0].stage("fragment")->vgprs);
}

TEST_CASE("a family radv does not know aborts the worker, not the caller") {
    const VariantBuild b = build_variant(default_variant());
    GpuTarget bogus{"bogus", "bogus", "none", ""};
    const auto runs = compile_on_targets({bogus}, {aco_source(b.languages[0], "v")},
                                         std::filesystem::current_path(), 1, kWatergen);
    REQUIRE(runs.size() == 1);
    CHECK_FALSE(runs[0].ok());
    CHECK(runs[0].error.find("bogus") != std::string::npos);
    CHECK(runs[0].error.find("signal 6") != std::string::npos);
}

TEST_CASE("a worker that dies inside the compiler names the pipeline it was compiling") {
    // A stand-in for a driver crash: the worker's protocol (compiling.txt, then the signal).
    const std::filesystem::path worker = std::filesystem::current_path() / "crashing_worker.sh";
    {
        std::ofstream script(worker);
        script << "#!/bin/sh\nprintf 'water glsl' > \"$2/compiling.txt\"\nkill -SEGV $$\n";
    }
    std::filesystem::permissions(worker, std::filesystem::perms::owner_all);
    const VariantBuild b = build_variant(default_variant());
    const auto runs =
        compile_on_targets({*find_gpu_target("rdna2")}, {aco_source(b.languages[0], "water glsl")},
                           std::filesystem::current_path(), 1, worker);
    CHECK_FALSE(runs[0].ok());
    CHECK(runs[0].error.find("rdna2 (navi21)") != std::string::npos);
    CHECK(runs[0].error.find("compiling water glsl") != std::string::npos);
    CHECK(runs[0].error.find("signal 11") != std::string::npos);
}

TEST_CASE("every covering variant's two paths compile on gcn4, rdna2 and rdna3") {
    std::vector<const VariantBuild*> builds;
    std::vector<std::string> names;
    for (const VariantBuild& b : test::covering_builds()) {
        REQUIRE(b.ok());
        builds.push_back(&b);
        names.push_back(b.shader.key());
    }
    std::string error;
    const auto targets = parse_gpu_targets({"gcn4,rdna2,rdna3"}, &error);
    REQUIRE(targets);
    const auto runs = variant_gpu_costs(*targets, builds, names, std::filesystem::current_path(),
                                        LoopUnroll::AsHinted, kWatergen);
    REQUIRE(runs.size() == 3);
    for (const auto& t : runs) {
        INFO(t.run.target.name << ": " << t.run.error);
        REQUIRE(t.run.ok());
        REQUIRE(t.costs.size() == 2 * builds.size());
        for (const PipelineGpuCost& c : t.costs) {
            INFO(c.name << ": " << c.error);
            REQUIRE(c.ok());
            const StageGpuCost* f = c.stage("fragment");
            REQUIRE(f);
            CHECK(f->instructions > 0);
            CHECK(f->vgprs > 0);
            CHECK(f->waves_per_simd > 0);
            // A covering variant's loops are the Gerstner search's and wave sums': every one is
            // matched, so each fragment stage has its per-pixel estimate.
            CHECK(f->per_pixel);
        }
    }
}

TEST_CASE("a pipeline the driver cannot create is named with what failed; the others compile") {
    const VariantBuild b = build_variant(default_variant());
    AcoPipelineSource broken = aco_source(b.languages[0], "broken");
    broken.fragment.clear();
    const GpuTarget* gcn4 = find_gpu_target("gcn4");
    const auto runs = compile_on_targets({*gcn4}, {aco_source(b.languages[0], "good"), broken},
                                         std::filesystem::current_path(), 1, kWatergen);
    REQUIRE(runs[0].ok());
    REQUIRE(runs[0].pipelines.size() == 2);
    CHECK(runs[0].pipelines[0].ok());
    CHECK(runs[0].pipelines[1].name == "broken");
    CHECK_FALSE(runs[0].pipelines[1].ok());
}

TEST_CASE("16-bit arithmetic on a family without it is reported, not compiled (gcn1 aborts)") {
    Variant v = default_variant();
    REQUIRE_FALSE(set_choice(v, "precision", "half"));
    const VariantBuild strict = build_variant(v, nullptr, EmitOptions{true});
    REQUIRE(strict.ok());
    const auto runs = compile_on_targets({*find_gpu_target("gcn1"), *find_gpu_target("rdna3")},
                                         {aco_source(strict.languages[0], "half")},
                                         std::filesystem::current_path(), 2, kWatergen);
    REQUIRE(runs[0].ok()); // the worker lived
    CHECK(runs[0].pipelines[0].unsupported);
    CHECK(runs[0].pipelines[0].error.find("no shaderFloat16") != std::string::npos);
    REQUIRE(runs[1].ok());
    CHECK(runs[1].pipelines[0].ok()); // rdna3 has 16-bit arithmetic
    // gcn1 has no listing (Mesa disassembles gfx6 through CLRX): static counts only.
    const VariantBuild full = build_variant(gerstner());
    const auto gcn1 = costs({"gcn1"}, full);
    const StageGpuCost* f = gcn1[0].costs[0].stage("fragment");
    CHECK_FALSE(f->per_pixel);
    CHECK(f->per_pixel_note.find("CLRX") != std::string::npos);
    CHECK(gcn1[0].costs[0].fragment_cost() == f->instructions);
}

namespace {

// The worker run on a job directory, as compile_on_targets runs it for rdna2: its exit and
// what it said.
std::string run_worker_on(const std::filesystem::path& dir) {
    const auto icd = radeon_icd();
    REQUIRE(icd);
    return run_child_process({kWatergen.string(), "gpu-worker", dir.string()}, dir,
                             {"VK_ICD_FILENAMES=" + icd->string(),
                              "VK_DRIVER_FILES=" + icd->string(), "RADV_FORCE_FAMILY=navi21",
                              "MESA_SHADER_CACHE_DISABLE=true"});
}

std::string read_all(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

} // namespace

TEST_CASE("the worker refuses a job it cannot give a driver, with exit 2 and the key") {
    const std::filesystem::path dir = std::filesystem::current_path() / "hostile-job";
    struct Case {
        std::string entry; // the pipeline's entry in job.json
        const char* says;
    };
    std::string many = "[";
    for (int i = 0; i < 100000; ++i)
        many += i ? ",2" : "2";
    many += "]";
    const std::string base = R"("name": "p", "specialization": {}, "tessellated": false, )";
    const Case cases[] = {
        {base + R"("format": 97, "geometry": {"attribute_sizes": )" + many + "}",
         "more than 16 vertex attributes"},
        {base + R"("format": 0)", "\"format\": expected a colour format"},
        {base + R"("format": -1)", "\"format\": expected a colour format"},
        {base + R"("format": 999999)", "\"format\": expected a colour format"},
        {base + R"("format": 126)", "\"format\": expected a colour format"}, // D32_SFLOAT
        {base + R"("format": 97, "geometry": {"attribute_sizes": [5]})", "an attribute of 5"},
        {base + R"("format": 97, "geometry": {"attribute_sizes": [2], "patch_control_points": 33})",
         "patch_control_points 33"},
        {R"("name": "p", "specialization": {"x": 1}, "format": 97)", "specialization 'x'"},
        {R"("name": "p", "specialization": {"0": 1e39}, "format": 97)", "finite 32-bit float"},
    };
    for (const Case& c : cases) {
        INFO(c.entry.substr(0, 200));
        std::filesystem::remove_all(dir);
        std::filesystem::create_directories(dir);
        std::ofstream(dir / "job.json")
            << R"({"disassembly": false, "pipelines": [{)" << c.entry << "}]}";
        const std::string failure = run_worker_on(dir);
        CHECK(failure.find("exit status 2") != std::string::npos);
        CHECK(failure.find(c.says) != std::string::npos);
    }
    std::filesystem::remove_all(dir);
}

TEST_CASE("the worker writes only its own files: compiling.txt is never followed as a link") {
    const std::filesystem::path dir = std::filesystem::current_path() / "linked-job";
    const std::filesystem::path outside = std::filesystem::current_path() / "outside.txt";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    std::ofstream(outside) << "untouched";
    const VariantBuild b = build_variant(default_variant());
    REQUIRE(write_aco_job(dir, {aco_source(b.languages[0], "water glsl")}, false).empty());
    std::filesystem::create_symlink(outside, dir / "compiling.txt");
    CHECK(run_worker_on(dir).empty());
    CHECK(read_all(outside) == "untouched");
    CHECK(std::filesystem::is_symlink(dir / "compiling.txt"));
    CHECK(std::filesystem::is_regular_file(dir / "result.json"));
    std::filesystem::remove_all(dir);
    std::filesystem::remove(outside);
}

TEST_CASE("a colour format the device does not render to is the pipeline's error, not a crash") {
    const VariantBuild b = build_variant(default_variant());
    AcoPipelineSource odd = aco_source(b.languages[0], "odd");
    odd.format = VK_FORMAT_R4G4_UNORM_PACK8; // a colour format, but no colour attachment
    const auto runs = compile_on_targets({*find_gpu_target("rdna2")}, {odd},
                                         std::filesystem::current_path(), 1, kWatergen);
    REQUIRE(runs[0].ok());
    REQUIRE(runs[0].pipelines.size() == 1);
    CHECK(runs[0].pipelines[0].error.find("cannot render to format 1") != std::string::npos);
}

TEST_CASE("a caller's VK_DRIVER_FILES does not choose the worker's driver") {
    // CI pins lavapipe this way; the worker must still open RADV's null device.
    const char* before = std::getenv("VK_DRIVER_FILES");
    const std::string kept = before ? before : "";
    ::setenv("VK_DRIVER_FILES", "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json", 1);
    ::setenv("VK_ADD_DRIVER_FILES", "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json", 1);
    const auto runs = costs({"rdna2"}, build_variant(gerstner()));
    if (before)
        ::setenv("VK_DRIVER_FILES", kept.c_str(), 1);
    else
        ::unsetenv("VK_DRIVER_FILES");
    ::unsetenv("VK_ADD_DRIVER_FILES");
    REQUIRE(runs.size() == 1);
    CHECK(runs[0].run.device.find("NAVI21") != std::string::npos);
}
