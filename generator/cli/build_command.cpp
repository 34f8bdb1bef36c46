// watergen build [MATERIAL] [--scene S ...] --out DIR: every variant the scenes need, folded,
// validated, optimised, cross-compiled and reflected in parallel, cached, written atomically.
#include <chrono>
#include <cstdio>
#include <memory>
#include <unistd.h>

#include <fmt/format.h>

#include "commands.h"
#include "watergen/eval/measure/driver_check.h"
#include "watergen/pipeline/build/build_files.h"
#include "watergen/pipeline/jobs/build_progress.h"
#include "watergen/water/binding_profiles.h"

namespace watergen::cli {

namespace {

void print_up_to_date(const BuildSummary& s, const std::string& out) {
    std::printf("%s\n", fmt::format("build: {} variants up to date ({} files verified, nothing "
                                    "rebuilt) in {:.3f} s -> {}",
                                    s.variants, s.files, s.seconds, out)
                            .c_str());
}

void print_summary(const BuildSummary& s, BuildMode mode, const std::string& mode_name,
                   const std::string& out, unsigned jobs) {
    const unsigned threads = jobs ? jobs : hardware_threads();
    const std::string rejected =
        s.cache_rejected == 0 ? std::string()
                              : fmt::format("; {} cache entr{} failed verification, rebuilt",
                                            s.cache_rejected, s.cache_rejected == 1 ? "y" : "ies");
    const std::string stages =
        s.stages.reused == 0
            ? std::string()
            : fmt::format("; {} stages compiled, {} reused", s.stages.compiled, s.stages.reused);
    std::string companions;
    if (s.passes > 0)
        companions += fmt::format(" + {} caustics pass{} ({} cached)", s.passes,
                                  s.passes == 1 ? "" : "es", s.passes_cached);
    if (s.frozen > 0)
        companions += fmt::format(" + {} frozen modules ({} cached)", s.frozen, s.frozen_cached);
    std::printf("%s\n",
                fmt::format("build: {} variants{} ({} built, {} cached, {} shared between "
                            "scenes, {} same shader as another variant, {} failed{}{}){} "
                            "in {:.2f} s on {} thread{}{}; peak memory {:.0f} MB",
                            s.variants,
                            mode == BuildMode::Permutations
                                ? std::string()
                                : fmt::format(" in {} {} shaders", s.shaders, mode_name),
                            s.built, s.cached, s.shared, s.same, s.failed, stages, rejected,
                            companions, s.seconds, threads, threads == 1 ? "" : "s",
                            s.ok() ? fmt::format(" -> {} ({} files)", out, s.files)
                                   : std::string("; nothing written, ") + out + " is unchanged",
                            double(peak_resident_bytes()) / 1e6)
                    .c_str());
}

} // namespace

bool load_material_and_scenes(const std::string& material_path,
                              const std::vector<std::string>& scene_paths, Material& material,
                              std::vector<SceneFacts>& scenes, const Common& common) {
    Diagnostics ds; // shown only when a file does not load
    if (watergen::load_material_and_scenes(material_path, scene_paths, material, scenes, ds))
        return true;
    print_diagnostics(ds, common);
    return false;
}

void add_mode_option(CLI::App& app, std::string& mode) {
    app.add_option("--mode", mode,
                   "build mode: permutations (default: one shader per variant), specialized (one "
                   "shader per material and precision, each axis a switch on a specialization "
                   "constant) or branching (the same, switching on uniform-block members)")
        ->check(CLI::Validator(
            [](std::string& text) -> std::string {
                if (parse_build_mode(text)) return "";
                return "unknown build mode '" + text + "'; expected one of " + build_mode_names();
            },
            "MODE"));
}

// --check-drivers: the written build's pipelines on the families' compilers; the exit code.
static int check_drivers(const std::string& out, const std::vector<GpuTarget>& targets) {
    std::string names;
    for (const auto& t : targets)
        names += (names.empty() ? "" : ", ") + t.name;
    const DriverCheck check =
        check_build_on_drivers(out, targets, std::filesystem::temp_directory_path());
    if (!check.error.empty()) return stop("--check-drivers: " + check.error, RunStatus::Failed);
    for (const auto& f : check.failures)
        std::fprintf(stderr, "watergen: error: --check-drivers: %s\n", f.c_str());
    if (check.no_device) return kNoDevice;
    if (!check.ok()) return kFailed;
    std::printf("checked %zu pipelines on %s (ACO, RADV's null device): every one compiled\n",
                check.pipelines, names.c_str());
    return kOk;
}

Runner add_build_command(CLI::App& app, const Common& common) {
    struct Options {
        std::string material;
        std::vector<std::string> scenes;
        std::string out;
        unsigned jobs = 0;
        std::string cache;
        bool no_cache = false;
        bool quiet = false;
        std::string mode = "permutations";
        bool freeze = false;
        std::string depfile;
        std::string shard;
        std::string bindings;
        std::vector<std::string> check_drivers;
    };
    auto o = std::make_shared<Options>();
    app.add_option("material", o->material,
                   "material description (JSON, see docs/user-guide.md \"Material files\"); "
                   "default: the built-in default material, the same as "
                   "examples/materials/default.json");
    app.add_option("--scene", o->scenes,
                   "scene description (JSON, repeatable); with scenes only the variants they reach "
                   "are built, each folded "
                   "under the scene's facts into <out>/<scene>/<variant>/; without, every variant "
                   "of the material goes "
                   "unfolded into <out>/unpruned/<variant>/");
    app.add_option("--out", o->out,
                   "output directory, replaced as a whole when the build succeeds; it must be an "
                   "earlier output of "
                   "watergen build, an empty directory or a path that does not exist")
        ->required();
    add_jobs_option(app, o->jobs,
                    "worker threads (default: every hardware thread); output is the same for any "
                    "count");
    app.add_option("--cache", o->cache,
                   "cache directory (default: $XDG_CACHE_HOME/watergen or ~/.cache/watergen)");
    app.add_flag("--no-cache", o->no_cache, "build every variant, and store nothing");
    app.add_flag("--quiet,-q", o->quiet, "no progress line, only the summary");
    add_mode_option(app, o->mode);
    app.add_flag("--freeze", o->freeze,
                 "with --mode specialized: also write each variant's SPIR-V with its selectors "
                 "frozen offline by spirv-opt (<shader>/<lang>/frozen/<variant>.frag.spv)");
    app.add_option("--depfile", o->depfile,
                   "also write a Makefile-style dependency file: target <out>/manifest.json, "
                   "prerequisites the material and scene files (for make, ninja, CMake DEPFILE)");
    app.add_option("--shard", o->shard,
                   "build only shard I of N (I/N, 1 <= I <= N): the variants (in specialized "
                   "and branching mode the shaders) whose key hashes to it, plus shard.json; "
                   "`watergen merge` joins the N outputs into what one build writes")
        ->check(CLI::Validator(
            [](std::string& text) {
                std::string why;
                return parse_shard(text, &why) ? std::string() : why;
            },
            "I/N"));
    app.add_option("--bindings", o->bindings,
                   "where every resource is bound in every target: a profile (" +
                       binding_profile_list() +
                       "; default watergen) or a binding map file (JSON, see docs/user-guide.md "
                       "\"Binding maps\"); one map serves every variant");
    app.add_option("--check-drivers", o->check_drivers,
                   "after the build, create every pipeline it wrote (each variant's GLSL and HLSL "
                   "paths, each companion pass) with these AMD families' compiler, ACO on RADV's "
                   "null device (no GPU needed; " +
                       gpu_target_names() +
                       "): the build fails naming each pipeline a driver refuses or crashes on")
        ->take_all();
    return [o, &common]() {
        std::optional<std::vector<GpuTarget>> drivers;
        if (!o->check_drivers.empty()) {
            if (!(drivers = resolve_targets(o->check_drivers, "--check-drivers"))) return kUsage;
            // Only AMD families are checked here (the tests render every variant on lavapipe):
            // a list with lavapipe would report pipelines it never created there.
            if (has_lavapipe(*drivers)) {
                std::fprintf(stderr,
                             "watergen: error: --check-drivers: lavapipe is not a driver "
                             "check (the render tests draw every variant on it); name "
                             "AMD families: %s\n",
                             amd_target_names().c_str());
                return kUsage;
            }
        }
        BuildFilesRequest request;
        request.material_path = o->material;
        request.scene_paths = o->scenes;
        request.out = o->out;
        request.mode = *parse_build_mode(o->mode);
        request.freeze = o->freeze;
        if (o->freeze && request.mode != BuildMode::Specialized) {
            std::fprintf(stderr,
                         "watergen: error: --freeze: freezes specialization constants; "
                         "expected --mode specialized, got --mode %s\n",
                         o->mode.c_str());
            return kUsage;
        }
        if (!o->shard.empty()) request.shard = *parse_shard(o->shard, nullptr);
        o->jobs = o->jobs ? capped_jobs(o->jobs) : 0;
        request.options.threads = o->jobs;
        if (!o->no_cache)
            request.options.cache = BuildCache(o->cache.empty() ? default_cache_dir()
                                                                : std::filesystem::path(o->cache));
        request.depfile = o->depfile;
        request.bindings = o->bindings;
        const bool tty = !o->quiet && ::isatty(STDERR_FILENO);
        // On a terminal a line redrawn after every job; in a log (CI) a line every 30 s, so
        // that a long build says where it is and a short one stays quiet.
        const auto start = std::chrono::steady_clock::now();
        auto last_line = std::make_shared<std::chrono::steady_clock::time_point>(start);
        const std::string jobs = request.mode == BuildMode::Permutations ? "variants" : "shaders";
        if (!o->quiet)
            request.options.progress = [tty, start, last_line, jobs](const BuildProgress& p) {
                const auto now = std::chrono::steady_clock::now();
                const double seconds = std::chrono::duration<double>(now - start).count();
                if (tty) {
                    std::fprintf(stderr, "\r\033[K%s  %s", progress_text(p, seconds, jobs).c_str(),
                                 p.key.substr(0, 50).c_str());
                } else {
                    if (now - *last_line < std::chrono::seconds(30)) return;
                    *last_line = now;
                    std::fprintf(stderr, "build: %s\n", progress_text(p, seconds, jobs).c_str());
                }
                std::fflush(stderr);
            };
        const BuildFilesRun run = build_from_files(request);
        if (!run.depfile_error.empty())
            return stop("--depfile: " + run.depfile_error,
                        run.depfile_refused ? RunStatus::BadInput : RunStatus::Failed);
        if (run.summary.up_to_date) {
            print_up_to_date(run.summary, o->out);
            return drivers ? check_drivers(o->out, *drivers) : kOk;
        }
        if (!run.built) return stop(run.load_diagnostics, "", RunStatus::BadInput, common);
        if (tty) std::fprintf(stderr, "\r\033[K");
        const BuildSummary& s = run.summary;
        print_diagnostics(s.diagnostics, common);
        if (s.bad_input) return kUsage;
        print_summary(s, request.mode, o->mode, o->out, o->jobs);
        if (!s.ok()) return kFailed;
        return drivers ? check_drivers(o->out, *drivers) : kOk;
    };
}

} // namespace watergen::cli
