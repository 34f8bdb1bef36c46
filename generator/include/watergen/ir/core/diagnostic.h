// Diagnostics are data: every stage returns them, only main() prints them.
#pragma once

#include <string>
#include <vector>

namespace watergen {

enum class Severity { Note, Warning, Error };

struct Diagnostic {
    Severity severity = Severity::Error;
    std::string file; // generated file name, description file, or "" when not tied to a file
    int line = 0;     // 1-based; 0 = unknown
    int column = 0;   // 1-based; 0 = unknown
    std::string node; // feature node that produced the offending code, "" when unknown
    std::string message;
};

using Diagnostics = std::vector<Diagnostic>;

inline bool has_errors(const Diagnostics& ds) {
    for (const auto& d : ds)
        if (d.severity == Severity::Error) return true;
    return false;
}

enum class DiagnosticFormat { Gcc, Msvc };

// GCC: "file:line:column: error: message [node: fresnel.schlick]"
// MSVC: "file(line,column): error: message [node: fresnel.schlick]"
std::string format_diagnostic(const Diagnostic& d, DiagnosticFormat format = DiagnosticFormat::Gcc);

} // namespace watergen
