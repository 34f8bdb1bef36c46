// The CLI's subcommands. Each registers its options on the app and returns the function that
// runs it; main() only parses and dispatches.
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

#include "watergen/diagnostic.h"
#include "watergen/variant.h"

namespace watergen::cli {

// Exit codes shared by every subcommand.
constexpr int kOk = 0;
constexpr int kFailed = 1;     // a shader failed to build or validate, or output could not be written
constexpr int kUsage = 2;      // bad flags or values
constexpr int kNoDevice = 3;   // no Vulkan device (runner commands)

struct Common {
    DiagnosticFormat format = DiagnosticFormat::Gcc;
};

using Runner = std::function<int()>;

// Adds --<axis> options for every axis, each restricted to its choices.
void add_variant_options(CLI::App& app, Variant& variant);
void print_diagnostics(const Diagnostics& ds, const Common& common);

Runner add_emit_command(CLI::App& app, const Common& common);
Runner add_bench_compile_command(CLI::App& bench, const Common& common);

} // namespace watergen::cli
