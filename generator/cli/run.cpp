// watergen: generate, validate and compare real-time water shaders. The command line of every
// generator: watergen's own, and a project's with its registered nodes (main.cpp).
#include <cstdio>
#include <map>
#include <new>
#include <string>
#include <vector>

#include "commands.h"
#include "watergen/plan/material.h"
#include "watergen/water/presets.h"
#include "watergen/water/water_shader.h"

namespace watergen::cli {

void add_variant_options(CLI::App& app, Variant& variant, std::string& preset) {
    std::vector<std::string> preset_list;
    for (const auto& p : presets())
        preset_list.push_back(p.name);
    app.add_option("--preset", preset, "parameter preset: " + preset_names())
        ->check(CLI::IsMember(preset_list));
    const auto& list = axes();
    for (size_t i = 0; i < list.size(); ++i) {
        std::vector<std::string> names;
        for (const auto& c : list[i].choices)
            names.push_back(c.name);
        app.add_option("--" + list[i].name, variant.choices[i], axis_help(list[i]))
            ->check(CLI::IsMember(names));
    }
}

bool resolve_variant(const Variant& variant, const std::string& preset_name, const Preset** preset,
                     const Common& common) {
    if (auto e = check_constraints(variant)) {
        std::fprintf(stderr, "watergen: error: %s\n", e->c_str());
        return false;
    }
    *preset = preset_name.empty() ? nullptr : find_preset(preset_name);
    // An error in composing the IR is in a node's definition (a description), not in the
    // toolchain: exit 2, as for a material file's mistake.
    const WaterShader composed = build_water_shader(variant, *preset);
    if (has_errors(composed.fragment.diagnostics())) {
        print_diagnostics(composed.fragment.diagnostics(), common);
        return false;
    }
    return true;
}

void print_diagnostics(const Diagnostics& ds, const Common& common) {
    for (const auto& d : ds)
        std::fprintf(stderr, "%s\n", format_diagnostic(d, common.format).c_str());
}

int exit_code(RunStatus status) {
    switch (status) {
    case RunStatus::Ok:
        return kOk;
    case RunStatus::BadInput:
        return kUsage;
    case RunStatus::Failed:
        return kFailed;
    case RunStatus::NoDevice:
        return kNoDevice;
    }
    return kFailed;
}

int stop(const Diagnostics& ds, const std::string& error, RunStatus status, const Common& common) {
    print_diagnostics(ds, common);
    return stop(error, status);
}

int stop(const std::string& error, RunStatus status) {
    if (!error.empty()) std::fprintf(stderr, "watergen: error: %s\n", error.c_str());
    return exit_code(status);
}

namespace {

// Every subcommand on `app`, each with the function that runs it.
void add_commands(CLI::App& app, const Common& common, std::map<CLI::App*, Runner>& runners) {
    CLI::App* emit =
        app.add_subcommand("emit", "emit one variant (or --covering: the covering set) in GLSL and "
                                   "HLSL, validated and cross-compiled");
    runners[emit] = add_emit_command(*emit, common);
    CLI::App* render = app.add_subcommand(
        "render",
        "render one variant on Vulkan (lavapipe) through both languages and compare with the CPU");
    runners[render] = add_render_command(*render, common);
    CLI::App* probe = app.add_subcommand(
        "probe", "numeric harness: one node over CSV input tuples on the GPU and the CPU");
    runners[probe] = add_probe_command(*probe, common);
    CLI::App* cost = app.add_subcommand(
        "cost", "instructions lavapipe executes for one draw of a variant, counted exactly "
                "under valgrind: a cost that machine load does not change");
    runners[cost] = add_cost_command(*cost, common);
    CLI::App* compare = app.add_subcommand(
        "compare", "variants side by side against a reference: images, error per view, draw "
                   "time (interleaved, A/A-checked) and instruction cost");
    runners[compare] = add_compare_command(*compare, common);
    CLI::App* caustics = app.add_subcommand(
        "caustics", "the caustics passes (area ratio, photon splatting) on the device against "
                    "the CPU photon reference: textures, pass time, error, energy");
    runners[caustics] = add_caustics_command(*caustics, common);
    CLI::App* pick = app.add_subcommand(
        "pick", "per scene, the cheapest variant whose error against the scene's gold stays "
                "within a budget, by instruction cost; writes it as a material file");
    runners[pick] = add_pick_command(*pick, common);
    CLI::App* bench = app.add_subcommand("bench", "benchmarks (print a table, write CSV and JSON)");
    bench->require_subcommand(1);
    CLI::App* compile = bench->add_subcommand(
        "compile", "in-process toolchain vs the same chain through command-line tools");
    runners[compile] = add_bench_compile_command(*compile, common);
    CLI::App* build = app.add_subcommand(
        "build", "build every variant a material's scenes need: pruned, folded, validated, "
                 "cross-compiled, cached, in parallel; writes manifest.json");
    runners[build] = add_build_command(*build, common);
    CLI::App* merge = app.add_subcommand(
        "merge", "join the outputs of `watergen build --shard I/N` (I = 1..N) into exactly what "
                 "one build writes");
    runners[merge] = add_merge_command(*merge);
    CLI::App* bindings = app.add_subcommand(
        "bindings", "print a binding map (a profile, or a checked file) with every slot spelled "
                    "out: where each resource is bound for Vulkan, HLSL, Metal and GL");
    runners[bindings] = add_bindings_command(*bindings, common);
    CLI::App* explain = app.add_subcommand(
        "explain", "which variants each scene skips and which terms it folds away, and why");
    runners[explain] = add_explain_command(*explain, common);
    CLI::App* bench_build = bench->add_subcommand(
        "build", "variants per second of watergen build: cold and warm cache, "
                 "one thread and all threads");
    runners[bench_build] = add_bench_build_command(*bench_build, common);
    CLI::App* bench_prune = bench->add_subcommand(
        "prune", "pruned against unpruned shaders per scene: SPIR-V size, GPU time, "
                 "image difference");
    runners[bench_prune] = add_bench_prune_command(*bench_prune, common);
    CLI::App* accuracy = bench->add_subcommand(
        "accuracy", "every cheaper choice against its axis' gold: GPU time ratio and image error");
    runners[accuracy] = add_bench_accuracy_command(*accuracy, common);
    CLI::App* half = bench->add_subcommand(
        "half", "the covering set's half variants in 16-bit arithmetic on the GPU: agreement "
                "with the CPU half model, error against full precision");
    runners[half] = add_bench_half_command(*half, common);
    CLI::App* agreement = bench->add_subcommand(
        "agreement", "the covering set through both languages against the CPU in float and "
                     "double, pixel by pixel within the tolerance plus the float error bound");
    runners[agreement] = add_bench_agreement_command(*agreement, common);
    CLI::App* unroll = bench->add_subcommand(
        "unroll", "kept loops against unrolled ones on lavapipe, per waves choice: shader size, "
                  "first draw (JIT) and steady draw, interleaved with an A/A pair");
    runners[unroll] = add_bench_unroll_command(*unroll, common);
    CLI::App* cpu = bench->add_subcommand(
        "cpu", "the CPU evaluator on the gold variant's reference image: per precision and "
               "thread count, interleaved rounds");
    runners[cpu] = add_bench_cpu_command(*cpu, common);
    CLI::App* modes = bench->add_subcommand(
        "modes", "the build modes side by side: build cost, SPIR-V size, pipeline, first and "
                 "steady draw per variant, image against the permutation");
    runners[modes] = add_bench_modes_command(*modes, common);
    CLI::App* geometry = bench->add_subcommand(
        "geometry", "per view, a variant as the screen pass, as meshes of several densities and "
                    "tessellated: error against the exact surface, vertex counts, draw time");
    runners[geometry] = add_bench_geometry_command(*geometry, common);
    CLI::App* stability = bench->add_subcommand(
        "stability", "the waves against the CPU in double as time runs (to a year) and the world "
                     "offset grows (to 1000 km), and at grazing elevations: every family, "
                     "precision and geometry");
    runners[stability] = add_bench_stability_command(*stability, common);
    // Hidden (no group): the child process of every ACO statistic (aco_worker.h).
    CLI::App* gpu_worker = app.add_subcommand("gpu-worker", "")->group("");
    runners[gpu_worker] = add_gpu_worker_command(*gpu_worker);
}

// "bench geometry" for bench's geometry subcommand.
std::string command_path(const CLI::App* sub) {
    std::string path = sub->get_name();
    for (const CLI::App* p = sub->get_parent(); p && p->get_parent(); p = p->get_parent())
        path = p->get_name() + " " + path;
    return path;
}

void add_paths(const CLI::App& app, std::vector<std::string>& out) {
    for (const CLI::App* sub : app.get_subcommands({})) {
        if (sub->get_subcommands({}).empty())
            out.push_back(command_path(sub));
        else
            add_paths(*sub, out);
    }
}

int run_unguarded(int argc, char** argv, const RunnerWrap& wrap) {
    // A project's generator (watergen_add_generator) registered its nodes before main: a failed
    // registration stops it before anything is built from a registry without them.
    if (const auto& errors = watergen::registration_errors(); !errors.empty()) {
        print_diagnostics(errors, Common{});
        return kUsage;
    }
    if (const auto error = watergen::check_registered_nodes()) {
        print_diagnostics({*error}, Common{});
        return kUsage;
    }
    CLI::App app{
        "watergen: generates real-time water shaders (GLSL + HLSL) from one C++ description,\n"
        "validates them with glslang and spirv-val, and cross-compiles them with SPIRV-Cross."};
    app.require_subcommand(1);
    Common common;
    std::string format = "gcc";
    app.add_option("--diagnostics-format", format,
                   "how errors are printed: gcc (file:line:col) or msvc (file(line,col))")
        ->check(CLI::IsMember({"gcc", "msvc"}));
    std::map<CLI::App*, Runner> runners;
    add_commands(app, common, runners);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "watergen: error: %s (see --help)\n", e.what());
        return kUsage;
    }
    common.format =
        format == "msvc" ? watergen::DiagnosticFormat::Msvc : watergen::DiagnosticFormat::Gcc;
    for (auto& [sub, runner] : runners)
        if (sub->parsed()) return wrap ? wrap(command_path(sub), runner)() : runner();
    return kUsage;
}

} // namespace

std::vector<std::string> command_paths() {
    CLI::App app;
    Common common;
    std::map<CLI::App*, Runner> runners;
    add_commands(app, common, runners);
    std::vector<std::string> paths;
    add_paths(app, paths);
    return paths;
}

int run_with(int argc, char** argv, const RunnerWrap& wrap) {
    // Nothing a command throws reaches main: a failure the code did not foresee (memory, a
    // library's exception) ends the run with exit 1 and what it was, and the destructors of
    // what it made (staging trees, scratch directories) remove their partial files.
    try {
        return run_unguarded(argc, argv, wrap);
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "watergen: error: out of memory\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "watergen: error: %s\n", e.what());
    } catch (...) {
        std::fprintf(stderr, "watergen: error: an unknown exception\n");
    }
    return kFailed;
}

int run(int argc, char** argv) {
    return run_with(argc, argv, {});
}

} // namespace watergen::cli
