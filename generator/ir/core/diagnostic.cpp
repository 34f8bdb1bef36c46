#include "watergen/ir/core/diagnostic.h"

#include <fmt/format.h>

namespace watergen {

std::string format_diagnostic(const Diagnostic& d, DiagnosticFormat format) {
    const char* severity = d.severity == Severity::Error     ? "error"
                           : d.severity == Severity::Warning ? "warning"
                                                             : "note";
    std::string where = d.file.empty() ? "watergen" : d.file;
    if (d.line > 0) {
        if (format == DiagnosticFormat::Gcc)
            where +=
                d.column > 0 ? fmt::format(":{}:{}", d.line, d.column) : fmt::format(":{}", d.line);
        else
            where += d.column > 0 ? fmt::format("({},{})", d.line, d.column)
                                  : fmt::format("({})", d.line);
    }
    std::string text = fmt::format("{}: {}: {}", where, severity, d.message);
    if (!d.node.empty()) text += fmt::format(" [node: {}]", d.node);
    return text;
}

} // namespace watergen
